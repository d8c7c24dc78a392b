#pragma once
// sin(πx) and cos(πx) together, for the samplers' angles (φ = 2π·u, the concentric map's π/4·b/a),
// from IEEE additions and multiplications alone:
//  - the same bits on every host and on the GPU (device code is built with --fmad=false, the host
//    with -ffp-contract=off), where libm's sin and cos differ between glibc and CUDA in last bits;
//  - no call into libm, so a loop over lanes of samples vectorises.
// Error within 2 ulp of the exact value for |x| < 2^50 (tests/math/trig_test.cpp measures it);
// ±∞ and NaN give NaN.

#include "strahl/math/config.h"

namespace strahl {

struct SinCos {
  Real sin, cos;
};

STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE SinCos sin_cos_pi(Real x) {
  // q: the integer nearest 2x (adding and subtracting 1.5·2^52 rounds to an integer), so that
  // x = q/2 + r with |r| ≤ 1/4, r exact (Sterbenz).
  constexpr Real kRound = 6755399441055744.0;
  const Real q = (2 * x + kRound) - kRound;
  const Real r = x - q * Real(0.5);
  // Taylor series of sin(πr)/r and cos(πr) in r²: with |πr| ≤ π/4 the first omitted terms are
  // below 1e-19 (they are (π/4)^19/19! and (π/4)^18/18!).
  const Real r2 = r * r;
  const Real s =
      r * (3.141592653589793 +
           r2 * (-5.16771278004997 +
                 r2 * (2.5501640398773455 +
                       r2 * (-0.5992645293207921 +
                             r2 * (0.08214588661112823 +
                                   r2 * (-0.0073704309457143504 +
                                         r2 * (0.00046630280576761255 +
                                               r2 * (-2.1915353447830217e-05 + r2 * 7.952054001475513e-07))))))));
  const Real c =
      1 + r2 * (-4.934802200544679 +
                r2 * (4.0587121264167685 +
                      r2 * (-1.3352627688545895 +
                            r2 * (0.2353306303588932 +
                                  r2 * (-0.02580689139001406 +
                                        r2 * (0.0019295743094039231 +
                                              r2 * (-0.0001046381049248457 + r2 * 4.303069587032947e-06)))))));
  // The quadrant m = q mod 4, as q − 4·round(q/4) ∈ {−2, …, 2}: sin(π(r + m/2)) and cos(π(r + m/2)).
  const Real m = q - 4 * ((q * Real(0.25) + kRound) - kRound);
  const bool odd = m == 1 || m == -1;
  const Real sin_abs = odd ? c : s, cos_abs = odd ? s : c;
  const bool sin_negative = m == 2 || m == -2 || m == -1, cos_negative = m == 2 || m == -2 || m == 1;
  return {sin_negative ? -sin_abs : sin_abs, cos_negative ? -cos_abs : cos_abs};
}

}  // namespace strahl
