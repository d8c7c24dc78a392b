#pragma once
// A packet's nearest hits in lane form, where each is a sphere, a plane or nothing (the lecture's
// shapes): the lanes' t and the index of the sphere or plane hit, one array each, as the packet
// loops over spheres and planes find them (render/intersect_packet.h) and surface_lanes() reads
// them (render/surface_lanes.h) — no Hit per lane written and read back in between. A lane's Hit
// is made only where a lane goes on alone.

#include <cstdint>

#include "strahl/geometry/hit.h"

namespace strahl {

template <int N>
struct HitLanes {
  Real t[N];       // the hit's t; kInfinity where none
  Real sphere[N];  // the index of the sphere hit, as a Real; −1 where the hit is not a sphere
  Real plane[N];   // the index of the plane hit, as a Real; −1 where the hit is not a plane

  // Lane i's Hit, as closest_hit() returns it.
  STRAHL_HOST_DEVICE Hit hit(int i) const {
    Hit h;
    h.t = t[i];
    h.kind = sphere[i] >= 0 ? ShapeKind::Sphere : plane[i] >= 0 ? ShapeKind::Plane : ShapeKind::None;
    h.index = sphere[i] >= 0 ? std::uint32_t(sphere[i]) : plane[i] >= 0 ? std::uint32_t(plane[i]) : 0;
    return h;
  }

  // The hits of the `active` lanes of hits[] (the other lanes: none) in lane form; false, and the
  // lanes unspecified, when one of them hit another kind of shape.
  STRAHL_HOST_DEVICE bool set(std::uint32_t active, const Hit* hits) {
    for (int i = 0; i < N; ++i) {
      const Hit& h = hits[i];
      const bool on = (active >> i) & 1u;
      if (on && h.kind != ShapeKind::None && h.kind != ShapeKind::Sphere && h.kind != ShapeKind::Plane) return false;
      t[i] = on && h.found() ? h.t : kInfinity;
      sphere[i] = on && h.kind == ShapeKind::Sphere ? Real(h.index) : Real(-1);
      plane[i] = on && h.kind == ShapeKind::Plane ? Real(h.index) : Real(-1);
    }
    return true;
  }

  // The lanes that hit a sphere or a plane (t is finite only there).
  STRAHL_HOST_DEVICE std::uint32_t found() const {
    std::uint32_t m = 0;
    for (int i = 0; i < N; ++i) m |= std::uint32_t(t[i] < kInfinity) << i;
    return m;
  }
};

}  // namespace strahl
