#pragma once
// A check shared by the tests of moving maps (tests/moving_solid_test.cpp, tests/spin_test.cpp):
// the box a map sweeps over each segment of the shutter (kernel::swept_bounds) holds the moved
// points of the box [lo, hi] at every time of the segment.

#include <initializer_list>
#include <random>
#include <string>

#include "strahl/geometry/moving_map.h"

namespace strahl::test {

// Empty when every check held, else where the first failed: for each count of equal segments,
// `points` points of the box at random times of each segment (its ends among them).
inline std::string swept_bounds_miss(const kernel::MovingMap& m, const Vec3& lo, const Vec3& hi,
                                     std::initializer_list<int> segment_counts, int points, std::mt19937_64& rng) {
  std::uniform_real_distribution<Real> f(0, 1);
  for (const int segments : segment_counts) {
    for (int k = 0; k < segments; ++k) {
      const Real u0 = Real(k) / segments, u1 = Real(k + 1) / segments;
      const Bounds b = kernel::swept_bounds(m, lo, hi, u0, u1);
      for (int i = 0; i < points; ++i) {
        const Vec3 p(lo.x + (hi.x - lo.x) * f(rng), lo.y + (hi.y - lo.y) * f(rng), lo.z + (hi.z - lo.z) * f(rng));
        const Real t = i == 0 ? u0 : (i == 1 ? u1 : u0 + (u1 - u0) * f(rng));
        const Vec3 q = kernel::moved_point(m, p, t);
        if (!(q.x >= b.lo.x && q.y >= b.lo.y && q.z >= b.lo.z && q.x <= b.hi.x && q.y <= b.hi.y && q.z <= b.hi.z))
          return "segment " + std::to_string(k) + " of " + std::to_string(segments) + ", time " + std::to_string(t);
      }
    }
  }
  return {};
}

}  // namespace strahl::test
