#pragma once
// Pearson's chi-square goodness-of-fit test for the sampling tests: observed bin counts against
// the counts a density predicts (pbrt-v4's approach: bins expecting fewer than 5 are pooled).

#include <cmath>
#include <vector>

namespace strahl::test {

// Regularised upper incomplete gamma function Q(a, x) (Numerical Recipes 6.2: series below
// a + 1, continued fraction above).
inline double gamma_q(double a, double x) {
  if (x <= 0) return 1;
  const double log_prefix = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1) {
    double sum = 1 / a, term = sum;
    for (int n = 1; n < 10000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::fabs(term) < std::fabs(sum) * 1e-15) break;
    }
    return 1 - sum * std::exp(log_prefix);
  }
  double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::fabs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::fabs(c) < 1e-300) c = 1e-300;
    d = 1 / d;
    const double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1) < 1e-15) break;
  }
  return std::exp(log_prefix) * h;
}

struct ChiSquare {
  double statistic = 0;
  int dof = 0;
  double p_value = 1;
};

// `expected` sums to the sample count. Bins expecting < 5 are pooled into one.
inline ChiSquare chi_square(const std::vector<double>& observed, const std::vector<double>& expected) {
  ChiSquare r;
  double pooled_obs = 0, pooled_exp = 0;
  int bins = 0;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < 5) {
      pooled_obs += observed[i];
      pooled_exp += expected[i];
      continue;
    }
    const double d = observed[i] - expected[i];
    r.statistic += d * d / expected[i];
    ++bins;
  }
  if (pooled_exp > 0) {
    const double d = pooled_obs - pooled_exp;
    r.statistic += d * d / pooled_exp;
    ++bins;
  } else if (pooled_obs > 0) {
    r.statistic = INFINITY;  // samples where the density says none can be
  }
  r.dof = bins - 1;
  r.p_value = r.dof > 0 ? gamma_q(r.dof / 2.0, r.statistic / 2.0) : 1;
  return r;
}

// Significance for one of `tests` tests at an overall level α (Šidák correction).
inline double significance(double alpha, int tests) { return 1 - std::pow(1 - alpha, 1.0 / tests); }

}  // namespace strahl::test
