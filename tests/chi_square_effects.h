#pragma once
// Pearson's chi-square test of observed bin counts against expected counts, for the Monte Carlo
// sampling routines of the distributed effects. Bins expected to hold fewer than 5 samples are
// pooled (pbrt's rule); the statistic is compared with the chi-square quantile at significance
// 1e-4 (Wilson–Hilferty), so a correct sampler fails about once in 10,000 seeds — and the
// samples here come from fixed seeds, so each run gives the same verdict.

#include <cmath>
#include <string>
#include <vector>

namespace strahl::test {

struct ChiSquareResult {
  double statistic = 0;
  double critical = 0;
  int dof = 0;
  bool pass = false;
  std::string describe() const {
    return "chi2 = " + std::to_string(statistic) + ", critical = " + std::to_string(critical) +
           ", dof = " + std::to_string(dof);
  }
};

inline ChiSquareResult chi_square(const std::vector<double>& observed, const std::vector<double>& expected) {
  ChiSquareResult r;
  double pooled_obs = 0, pooled_exp = 0;
  int bins = 0;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < 5) {
      pooled_obs += observed[i];
      pooled_exp += expected[i];
      // A bin that should be empty but is not, beyond any doubt: fail outright.
      if (expected[i] == 0 && observed[i] > 0) r.statistic = INFINITY;
      continue;
    }
    const double d = observed[i] - expected[i];
    r.statistic += d * d / expected[i];
    ++bins;
  }
  if (pooled_exp >= 5) {
    const double d = pooled_obs - pooled_exp;
    r.statistic += d * d / pooled_exp;
    ++bins;
  }
  r.dof = bins - 1;
  const double k = r.dof, z = 3.719;  // the standard normal's 1 − 1e-4 quantile
  r.critical = k * std::pow(1 - 2 / (9 * k) + z * std::sqrt(2 / (9 * k)), 3);
  r.pass = r.statistic <= r.critical;
  return r;
}

}  // namespace strahl::test
