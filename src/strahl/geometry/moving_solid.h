#pragma once
// A moving solid (motion blur, docs/scene-format.md "Motion"): any solid — a box, a cylinder, a
// torus, an implicit surface, an ellipsoid, a CSG tree — carried by an affine map that moves
// linearly from shutter open to close, as a moving mesh's vertices do: at time u ∈ [0, 1] a point
// p of the unmoved solid is at A(u)·p, A(u) = (1 − u)·A₀ + u·A₁ (so each point moves on a
// segment, and a box solid moves exactly as a mesh of its faces would). A ray meets it where it is
// at the ray's time: the ray is brought into the unmoved solid's space by A(u)⁻¹ (the placement
// of geometry/placement.h, computed per ray), where its t is the same, and the normal comes back
// by A(u)⁻ᵀ. scene/move_solid.h checks that A(u) is invertible at every u.

#include <initializer_list>

#include "strahl/geometry/moving.h"
#include "strahl/geometry/placement.h"
#include "strahl/geometry/solid.h"

namespace strahl::kernel {

struct MovingSolid {
  Solid solid;                   // the unmoved solid (it may be placed: its own transform comes first)
  Vec3 linear0[3], linear1[3];   // A's linear part at shutter open and at close, by rows
  Vec3 translate0, translate1;   // A's translation at shutter open and at close
  Vec3 lo, hi;                   // the unmoved solid's bounds
};

// world → the unmoved solid's space at time u: A(u)⁻¹, by cofactors. A velocity's linear part is
// the identity at both keys, and so exactly the identity here: such a solid is met where the ray
// itself, displaced, meets the unmoved solid.
STRAHL_HOST_DEVICE inline Placement at_time(const MovingSolid& m, Real u) {
  const Vec3 r0 = lerp(m.linear0[0], m.linear1[0], u), r1 = lerp(m.linear0[1], m.linear1[1], u),
             r2 = lerp(m.linear0[2], m.linear1[2], u);
  const Vec3 c0 = cross(r1, r2), c1 = cross(r2, r0), c2 = cross(r0, r1);
  const Real inv_det = 1 / dot(r0, c0);
  Placement x;
  x.row[0] = Vec3(c0.x, c1.x, c2.x) * inv_det;
  x.row[1] = Vec3(c0.y, c1.y, c2.y) * inv_det;
  x.row[2] = Vec3(c0.z, c1.z, c2.z) * inv_det;
  x.translate = lerp(m.translate0, m.translate1, u);
  return x;
}

// Where A(u) takes p (host: bounds).
inline Vec3 moved_point(const MovingSolid& m, const Vec3& p, Real u) {
  const Vec3 r0 = lerp(m.linear0[0], m.linear1[0], u), r1 = lerp(m.linear0[1], m.linear1[1], u),
             r2 = lerp(m.linear0[2], m.linear1[2], u);
  return Vec3(dot(r0, p), dot(r1, p), dot(r2, p)) + lerp(m.translate0, m.translate1, u);
}

// The box holding the solid at every time of [u0, u1]: each point of it moves on a segment
// between where A(u0) and A(u1) put it, and lies in the hull of the moved corners of its box (up
// to rounding, as a placed solid's box: geometry/solid_leaf.h).
inline Bounds swept_bounds(const MovingSolid& m, Real u0, Real u1) {
  Bounds box;
  for (const Real u : {u0, u1})
    for (int c = 0; c < 8; ++c)
      box.extend(moved_point(m, Vec3((c & 1) ? m.hi.x : m.lo.x, (c & 2) ? m.hi.y : m.lo.y, (c & 4) ? m.hi.z : m.lo.z), u));
  return box;
}
inline Bounds swept_bounds(const MovingSolid& m) { return swept_bounds(m, 0, 1); }

}  // namespace strahl::kernel
