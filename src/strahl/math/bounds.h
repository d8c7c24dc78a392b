#pragma once
// Axis-aligned bounding box and the slab test.

#include <cmath>
#include <limits>

#include "strahl/math/ray.h"

namespace strahl {

// γ₃ = 3u/(1 − 3u), u the unit roundoff of Real (Pharr, Jakob, Humphreys: PBR 3.9).
inline constexpr Real kSlabGamma3 =
    3 * (std::numeric_limits<Real>::epsilon() / 2) / (1 - 3 * (std::numeric_limits<Real>::epsilon() / 2));

struct Bounds {
  Vec3 lo{kInfinity}, hi{-kInfinity};

  STRAHL_HOST_DEVICE void extend(const Vec3& p) { lo = min(lo, p); hi = max(hi, p); }
  STRAHL_HOST_DEVICE bool empty() const { return lo.x > hi.x; }
};

// The box holding both boxes.
STRAHL_HOST_DEVICE inline Bounds merge(const Bounds& a, const Bounds& b) { return Bounds{min(a.lo, b.lo), max(a.hi, b.hi)}; }

// The box's surface area (0 for an empty box): the SAH's measure of how likely a ray meets it.
inline Real surface_area(const Bounds& b) {
  if (b.empty()) return 0;
  const Vec3 d = b.hi - b.lo;
  return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// Slab test with precomputed 1/direction: does the ray meet the box within (t_min, t_max)?
STRAHL_HOST_DEVICE inline bool hits(const Bounds& b, const Vec3& origin, const Vec3& inv_dir, Real t_min, Real t_max) {
  for (int a = 0; a < 3; ++a) {
    Real t0 = (b.lo[a] - origin[a]) * inv_dir[a];
    Real t1 = (b.hi[a] - origin[a]) * inv_dir[a];
    if (t0 > t1) { const Real tmp = t0; t0 = t1; t1 = tmp; }
    // Widen by the rounding error of the two operations above (pbrt's 1 + 2γ₃), so hits exactly
    // on a box face (vertices, axis-aligned edges, flat boxes) are not culled.
    t1 *= 1 + 2 * kSlabGamma3;
    t_min = t0 > t_min ? t0 : t_min;  // NaN (0·inf) keeps the old bound
    t_max = t1 < t_max ? t1 : t_max;
    if (t_min > t_max) return false;
  }
  return true;
}

}  // namespace strahl
