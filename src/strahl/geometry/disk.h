#pragma once
// A flat disk: centre, unit normal, radius. Not a solid (no inside); one crossing at most.

#include "strahl/geometry/solid_crossing.h"

namespace strahl::kernel {

struct Disk {
  Vec3 center;
  Vec3 normal;  // unit
  Real radius = 1;
};

STRAHL_HOST_DEVICE inline void line_crossings(const Disk& k, const Ray& ray, CrossingList& out) {
  const Real dn = dot(ray.direction, k.normal);
  if (dn == 0) return;
  const Real t = dot(k.center - ray.origin, k.normal) / dn;
  const Vec3 r = ray.at(t) - k.center;
  // Distance from the centre within the disk's plane (the offset along the normal is rounding).
  const Vec3 in_plane = r - k.normal * dot(r, k.normal);
  if (dot(in_plane, in_plane) <= k.radius * k.radius) out.add(t, 0, dn < 0);
}

}  // namespace strahl::kernel
