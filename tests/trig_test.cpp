// sin_cos_pi (math/trig.h), strahl's own sin(πx) and cos(πx): within 2 ulp of the exact value
// (long double reference), exact at the multiples of 1/2, NaN for ±∞ and NaN.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "strahl/math/trig.h"
#include "test_random.h"

namespace strahl::trig_test {
namespace {

// |value − exact| in units of the last place of the double nearest the exact value.
double ulps(double value, long double exact) {
  const double nearest = double(exact);
  const double ulp = nearest == 0 ? std::numeric_limits<double>::denorm_min()
                                  : std::nextafter(std::fabs(nearest), std::numeric_limits<double>::infinity()) -
                                        std::fabs(nearest);
  return double(std::fabs((long double)value - exact) / ulp);
}

constexpr long double kPiLong = 3.141592653589793238462643383279502884L;

// The reference: x = k/2 + r with |r| ≤ 1/4 (std::remainder is exact), then sinl and cosl of
// π·r in long double (64-bit mantissa: within 2^-63 relative of the exact value, far below a
// double's ulp, also near the zeros of sin(πx) and cos(πx)) and the quadrant k mod 4.
struct Reference {
  long double sin, cos;
};
Reference sin_cos_pi_ref(double x) {
  const double r = std::remainder(x, 0.5);
  const long double s = sinl(kPiLong * r), c = cosl(kPiLong * r);
  const int quadrant = int(std::fmod(std::fmod(std::round((x - r) * 2), 4.0) + 4.0, 4.0));
  switch (quadrant) {
    case 0: return {s, c};
    case 1: return {c, -s};
    case 2: return {-s, -c};
    default: return {-c, s};
  }
}

TEST(SinCosPi, WithinTwoUlpsOfTheExactValue) {
  test::Random random(41);
  double worst_sin = 0, worst_cos = 0;
  for (int i = 0; i < 2'000'000; ++i) {
    // The samplers' range ([0, 2] for φ = 2π·u) most, then wider and larger arguments.
    const double x = i % 4 == 0   ? random.uniform(-1e6, 1e6)
                     : i % 4 == 1 ? random.uniform(-4, 4)
                                  : random.uniform(0, 2);
    const SinCos sc = sin_cos_pi(x);
    const Reference ref = sin_cos_pi_ref(x);
    worst_sin = std::max(worst_sin, ulps(sc.sin, ref.sin));
    worst_cos = std::max(worst_cos, ulps(sc.cos, ref.cos));
  }
  EXPECT_LE(worst_sin, 2.0);
  EXPECT_LE(worst_cos, 2.0);
  // Near the zeros, where a reduction that is not exact would lose every digit.
  for (const double k : {0.0, 0.5, 1.0, 1.5, 2.0, -0.5, -1.0, 1e6 + 0.5}) {
    for (const double eps : {1e-300, 1e-17, 1e-12, 3e-9, 1e-5, -1e-15, -1e-7}) {
      const double x = k + eps;
      const SinCos sc = sin_cos_pi(x);
      const Reference ref = sin_cos_pi_ref(x);
      EXPECT_LE(ulps(sc.sin, ref.sin), 2.0) << x;
      EXPECT_LE(ulps(sc.cos, ref.cos), 2.0) << x;
    }
  }
}

TEST(SinCosPi, ExactAtMultiplesOfOneHalf) {
  for (int k = -16; k <= 16; ++k) {
    const SinCos sc = sin_cos_pi(k * 0.5);
    const int quadrant = ((k % 4) + 4) % 4;
    EXPECT_EQ(sc.sin, (quadrant == 1 ? 1.0 : quadrant == 3 ? -1.0 : 0.0)) << k;
    EXPECT_EQ(sc.cos, (quadrant == 0 ? 1.0 : quadrant == 2 ? -1.0 : 0.0)) << k;
  }
  const SinCos eighth = sin_cos_pi(0.25);
  EXPECT_LE(ulps(eighth.sin, sqrtl(0.5L)), 1.0);
  EXPECT_LE(ulps(eighth.cos, sqrtl(0.5L)), 1.0);
}

TEST(SinCosPi, NotANumberForInfinitiesAndNaN) {
  for (const double x : {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                         std::numeric_limits<double>::quiet_NaN()}) {
    const SinCos sc = sin_cos_pi(x);
    EXPECT_TRUE(std::isnan(sc.sin)) << x;
    EXPECT_TRUE(std::isnan(sc.cos)) << x;
  }
}

}  // namespace
}  // namespace strahl::trig_test
