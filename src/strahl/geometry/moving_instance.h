#pragma once
// A moving instance (motion blur, docs/scene-format.md "Instances"): an instance of a group
// carried, after its own placement, by the map A(u) of geometry/moving_map.h — and, for an
// instance that moves inside a group whose instance moves too (a wheel spinning on a car that
// turns a corner, a top spinning about an axis that precesses), then by a second such map B(u):
// x ↦ B(u)·A(u)·(placement of x). A ray at time u is brought by (B(u)·A(u))⁻¹ to where the
// instance stands still, and from there into the group's space as for any instance
// (geometry/instance.h); normals come back through both maps.

#include "strahl/geometry/instance.h"
#include "strahl/geometry/moving_map.h"

namespace strahl::kernel {

struct MovingInstance {
  Instance instance;  // the unmoved instance
  MovingMap map;      // A
  Vec3 lo, hi;        // the unmoved instance's world box
  // Bounds over the shutter of how much the group → world map lengthens and of its translation's
  // largest component (ray offsets, as Instance::stretch and Instance::shift).
  Real stretch = 1, shift = 0;
  std::uint32_t two_maps = 0;
  MovingMap outer;  // B, where two_maps is 1 (else unused: A alone carries the instance; last, so
                    // that a record with one map is read from the same lines as before)
};

// world → the unmoved instance at time u: A(u)⁻¹, or A(u)⁻¹·B(u)⁻¹. With b = B(u)⁻¹ (p ↦
// Rb·(p − tb)) and a = A(u)⁻¹ (q ↦ Ra·(q − ta)): p ↦ Ra·Rb·(p − (tb + Rb⁻¹·ta)), Rb⁻¹ being
// B(u)'s own linear part.
STRAHL_HOST_DEVICE inline Placement at_time(const MovingInstance& m, Real u) {
  Placement x = at_time(m.map, u);  // a
  if (m.two_maps == 0) return x;
  const Placement b = at_time(m.outer, u);
  Vec3 forward[3];
  inverse_rows(b.row[0], b.row[1], b.row[2], forward);
  x.translate = b.translate + Vec3(dot(forward[0], x.translate), dot(forward[1], x.translate), dot(forward[2], x.translate));
  for (Vec3& row : x.row) row = b.row[0] * row.x + b.row[1] * row.y + b.row[2] * row.z;
  return x;
}

// The box of the instance over [u0, u1]: A's sweep of its box, then B's sweep of that box (B(u)
// takes A(u)'s points, which lie in A's sweep, into B's sweep of it at every u).
inline Bounds swept_bounds(const MovingInstance& m, Real u0, Real u1) {
  const Bounds a = swept_bounds(m.map, m.lo, m.hi, u0, u1);
  return m.two_maps == 0 ? a : swept_bounds(m.outer, a.lo, a.hi, u0, u1);
}
inline Bounds swept_bounds(const MovingInstance& m) { return swept_bounds(m, 0, 1); }

}  // namespace strahl::kernel
