#pragma once
// The map that carries a moving solid or instance (motion blur; geometry/moving_solid.h,
// geometry/moving_instance.h): an affine map A(u) = (1 − u)·A₀ + u·A₁ over the shutter fraction
// u ∈ [0, 1], as a moving mesh's vertices move (each point on a segment). A ray at time u is
// brought to the unmoved object by A(u)⁻¹ (a placement, geometry/placement.h), where its t is the
// same; normals come back by A(u)⁻ᵀ. scene/move_solid.h checks that A(u) is invertible at every u.

#include <cstdint>
#include <initializer_list>

#include "strahl/geometry/moving.h"
#include "strahl/geometry/placement.h"
#include "strahl/math/bounds.h"

namespace strahl::kernel {

struct MovingMap {
  Vec3 linear0[3], linear1[3];   // A's linear part at shutter open and at close, by rows
  Vec3 translate0, translate1;   // A's translation at shutter open and at close
  // Where the linear part is the same at both keys (a velocity, keyframes that only translate),
  // its inverse, the same at every u: the one at_time() would compute, bit for bit.
  Vec3 fixed_inverse[3];
  std::uint32_t fixed = 0;
};

// The inverse of the linear part with rows r0, r1, r2, by cofactors.
STRAHL_HOST_DEVICE inline void inverse_rows(const Vec3& r0, const Vec3& r1, const Vec3& r2, Vec3* out) {
  const Vec3 c0 = cross(r1, r2), c1 = cross(r2, r0), c2 = cross(r0, r1);
  const Real inv_det = 1 / dot(r0, c0);
  out[0] = Vec3(c0.x, c1.x, c2.x) * inv_det;
  out[1] = Vec3(c0.y, c1.y, c2.y) * inv_det;
  out[2] = Vec3(c0.z, c1.z, c2.z) * inv_det;
}

// world → the unmoved object's space at time u: A(u)⁻¹. A velocity's linear part is the identity
// at both keys, and so exactly the identity here: such an object is met where the ray itself,
// displaced, meets the unmoved one.
STRAHL_HOST_DEVICE inline Placement at_time(const MovingMap& m, Real u) {
  Placement x;
  x.translate = lerp(m.translate0, m.translate1, u);
  if (m.fixed != 0) {
    x.row[0] = m.fixed_inverse[0];
    x.row[1] = m.fixed_inverse[1];
    x.row[2] = m.fixed_inverse[2];
    return x;
  }
  const Vec3 r0 = lerp(m.linear0[0], m.linear1[0], u), r1 = lerp(m.linear0[1], m.linear1[1], u),
             r2 = lerp(m.linear0[2], m.linear1[2], u);
  inverse_rows(r0, r1, r2, x.row);
  return x;
}

// Where A(u) takes p (host: bounds).
inline Vec3 moved_point(const MovingMap& m, const Vec3& p, Real u) {
  const Vec3 r0 = lerp(m.linear0[0], m.linear1[0], u), r1 = lerp(m.linear0[1], m.linear1[1], u),
             r2 = lerp(m.linear0[2], m.linear1[2], u);
  return Vec3(dot(r0, p), dot(r1, p), dot(r2, p)) + lerp(m.translate0, m.translate1, u);
}

// The box holding everything within the box [lo, hi] at every time of [u0, u1]: each point
// moves on a segment between where A(u0) and A(u1) put it, and lies in the hull of the moved
// corners (up to rounding, as a placed solid's box: geometry/solid_leaf.h).
inline Bounds swept_bounds(const MovingMap& m, const Vec3& lo, const Vec3& hi, Real u0, Real u1) {
  Bounds box;
  for (const Real u : {u0, u1})
    for (int c = 0; c < 8; ++c)
      box.extend(moved_point(m, Vec3((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z), u));
  return box;
}

}  // namespace strahl::kernel
