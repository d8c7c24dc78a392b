#pragma once
// A moving solid (motion blur, docs/scene-format.md "Moving solids"): any bounded solid — a box,
// a cylinder, a torus, an implicit surface, an ellipsoid, a CSG tree — carried by the map A(u) of
// geometry/moving_map.h, so each of its points moves on a segment and a box solid moves exactly as
// a mesh of its faces would. A ray at time u meets it where the ray brought by A(u)⁻¹ meets the
// unmoved solid (render/moving_shapes.h).

#include "strahl/geometry/moving_map.h"
#include "strahl/geometry/solid.h"

namespace strahl::kernel {

struct MovingSolid {
  Solid solid;    // the unmoved solid (it may be placed: its own transform comes first)
  MovingMap map;  // A
  Vec3 lo, hi;    // the unmoved solid's bounds
};

STRAHL_HOST_DEVICE inline Placement at_time(const MovingSolid& m, Real u) { return at_time(m.map, u); }

inline Bounds swept_bounds(const MovingSolid& m, Real u0, Real u1) { return swept_bounds(m.map, m.lo, m.hi, u0, u1); }
inline Bounds swept_bounds(const MovingSolid& m) { return swept_bounds(m, 0, 1); }

}  // namespace strahl::kernel
