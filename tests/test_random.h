#pragma once
// Reproducible random test data (Mersenne Twister from a fixed seed): numbers, points in a cube,
// unit directions (rejection from the unit ball).

#include <cmath>
#include <cstdint>
#include <random>

#include "strahl/math/vec3.h"

namespace strahl::test {

class Random {
 public:
  explicit Random(std::uint64_t seed) : rng_(seed) {}
  Real uniform(Real lo = 0, Real hi = 1) { return lo + (hi - lo) * Real(rng_() >> 11) * 0x1.0p-53; }
  int below(int n) { return int(rng_() % std::uint64_t(n)); }
  bool coin() { return (rng_() & 1u) != 0; }
  Real log_uniform(Real lo, Real hi) { return lo * std::pow(hi / lo, uniform()); }
  Vec3 point(Real lo, Real hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }
  Vec3 direction() {
    for (;;) {
      const Vec3 v = point(-1, 1);
      const Real l2 = length_squared(v);
      if (l2 > 1e-6 && l2 <= 1) return v / std::sqrt(l2);
    }
  }

 private:
  std::mt19937_64 rng_;
};

}  // namespace strahl::test
