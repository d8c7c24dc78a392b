#pragma once
// A moving instance (motion blur, docs/scene-format.md "Instances"): an instance of a group
// carried, after its own placement, by the map A(u) of geometry/moving_map.h. A ray at time u is
// brought by A(u)⁻¹ to where the instance stands still, and from there into the group's space as
// for any instance (geometry/instance.h); normals come back through both maps.

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
};

inline Bounds swept_bounds(const MovingInstance& m, Real u0, Real u1) { return swept_bounds(m.map, m.lo, m.hi, u0, u1); }
inline Bounds swept_bounds(const MovingInstance& m) { return swept_bounds(m, 0, 1); }

}  // namespace strahl::kernel
