#pragma once
// Real roots of polynomials up to degree four within an interval, by bracketing alone: the roots
// of the derivative split [lo, hi] into pieces on which the polynomial is monotone, and each
// piece whose ends differ in sign holds exactly one root, found by Newton steps kept inside the
// bracket (the bracket's secant where a step would leave it). The derivative's roots come the
// same way from its derivative, down to the quadratic's closed form. Unlike
// Ferrari's closed form this cannot lose a root to cancellation between its resolvent's terms:
// every root comes out of a bracket of f itself, to the last bits of double.

#include <cmath>

#include "strahl/math/config.h"

namespace strahl::kernel {

// c[0] + c[1]·x + … + c[degree]·x^degree (Horner).
STRAHL_HOST_DEVICE inline Real polynomial(const Real* c, int degree, Real x) {
  Real v = c[degree];
  for (int i = degree - 1; i >= 0; --i) v = v * x + c[i];
  return v;
}

// The one root of a polynomial monotone on [a, b] with f(a) = fa, f(b) = fb of opposite signs.
// Newton steps from the middle, the bracket shrinking around them. Where a step would leave the
// bracket — at the root's rounding level, where Newton has converged from one side and the other
// end is still far, or where the polynomial's curvature throws it out — the bracket's secant
// (regula falsi) takes its place, a double inside either end where it falls on one: so the far
// end comes to the root's other side in a step or two, not by halves. Should Newton fail again
// right after a secant step, the bracket is bisected instead.
STRAHL_HOST_DEVICE inline Real monotone_root(const Real* c, int degree, Real a, Real b, Real fa, Real fb) {
  Real d[4];
  for (int i = 1; i <= degree; ++i) d[i - 1] = Real(i) * c[i];
  Real x = Real(0.5) * (a + b);
  bool secant = false;  // the last step was the secant's
  for (int iter = 0; iter < 200; ++iter) {
    const Real f = polynomial(c, degree, x);
    if (f == 0) return x;
    if ((f < 0) == (fa < 0)) {
      a = x;
      fa = f;
    } else {
      b = x;
      fb = f;
    }
    const Real mid = a + Real(0.5) * (b - a);
    if (!(mid > a && mid < b)) return x;  // the bracket is down to adjacent doubles
    Real next = x - f / polynomial(d, degree - 1, x);
    if (next > a && next < b) {
      secant = false;
    } else if (secant) {
      next = mid;  // twice in a row: bisect, so the bracket at least halves every other step
      secant = false;
    } else {
      next = a + fa / (fa - fb) * (b - a);
      if (next >= b) next = std::nextafter(b, a);
      else if (next <= a) next = std::nextafter(a, b);
      if (!(next > a && next < b)) next = mid;  // (NaN)
      secant = true;
    }
    if (next == x) return x;
    x = next;
  }
  return x;
}

// The roots in [lo, hi] of a polynomial of degree Degree (1..4) whose leading coefficient is not
// 0, in ascending order; returns how many. A root where f touches 0 without changing sign is
// reported only where f is exactly 0 (a ray grazing a surface).
template <int Degree>
STRAHL_HOST_DEVICE inline int polynomial_roots(const Real* c, Real lo, Real hi, Real* roots) {
  if constexpr (Degree == 1) {
    const Real x = -c[0] / c[1];
    if (x >= lo && x <= hi) {
      roots[0] = x;
      return 1;
    }
    return 0;
  } else {
    // Critical points: the derivative's roots.
    Real d[Degree], crit[Degree - 1];
    for (int i = 1; i <= Degree; ++i) d[i - 1] = Real(i) * c[i];
    const int n_crit = polynomial_roots<Degree - 1>(d, lo, hi, crit);
    int n = 0;
    Real a = lo, fa = polynomial(c, Degree, lo);
    if (fa == 0) roots[n++] = lo;
    for (int i = 0; i <= n_crit; ++i) {
      const Real b = i < n_crit ? crit[i] : hi;
      if (!(b > a)) continue;
      const Real fb = polynomial(c, Degree, b);
      if (fb == 0) {
        if (n == 0 || roots[n - 1] != b) roots[n++] = b;
      } else if (fa != 0 && (fa < 0) != (fb < 0)) {
        roots[n++] = monotone_root(c, Degree, a, b, fa, fb);
      }
      a = b;
      fa = fb;
    }
    return n;
  }
}

}  // namespace strahl::kernel
