#pragma once
// A truncated cone between two end points with a radius at each (POV-Ray's cone); the cylinder is
// the cone with equal radii. Capped (a closed solid) or open (the lateral surface alone). In the
// cone's own frame (z along the axis from base to cap, 0 ≤ z ≤ h) the lateral surface is
// x² + y² = (r0 + k·z)², k = (r1 − r0)/h: a quadratic in the ray's distance, formed from the
// origin moved next to the cone (solid_crossing.h: ShiftedRay). Parts: 0 side, 1 base cap, 2 cap.

#include "strahl/geometry/solid_crossing.h"

namespace strahl::kernel {

struct Cone {
  Vec3 base;
  Vec3 axis;          // unit, from base to cap
  Real height = 1;    // |cap − base|
  Real base_radius = 1, cap_radius = 1;
  bool open = false;  // no caps
};

STRAHL_HOST_DEVICE inline void line_crossings(const Cone& c, const Ray& ray, CrossingList& out) {
  const ShiftedRay r = shifted_ray(ray, c.base + c.axis * (Real(0.5) * c.height));
  const Real k = (c.cap_radius - c.base_radius) / c.height;
  const Vec3 o = r.origin - c.base;
  const Real oz = dot(o, c.axis), dz = dot(r.direction, c.axis);
  const Vec3 op = o - c.axis * oz, dp = r.direction - c.axis * dz;
  // |op + u·dp|² = (c0 + c1·u)²
  const Real c0 = c.base_radius + k * oz, c1 = k * dz;
  const Real a = dot(dp, dp) - c1 * c1;
  const Real b = 2 * (dot(op, dp) - c0 * c1);
  const Real cc = dot(op, op) - c0 * c0;
  Real roots[2];
  const int n = quadratic_roots(a, b, cc, roots);
  for (int i = 0; i < n; ++i) {
    const Real z = oz + roots[i] * dz;
    // Entering where the quadratic falls through zero (the side's outward gradient against d).
    if (z >= 0 && z <= c.height) out.add(r.t(roots[i]), 0, 2 * a * roots[i] + b < 0);
  }
  if (!c.open && dz != 0) {
    const Real caps[2] = {0, c.height}, radii[2] = {c.base_radius, c.cap_radius};
    for (int i = 0; i < 2; ++i) {
      if (!(radii[i] > 0)) continue;
      const Real u = (caps[i] - oz) / dz;
      const Vec3 q = op + dp * u;
      // The base's outward normal is −axis: entering it means moving along +axis.
      if (dot(q, q) <= radii[i] * radii[i]) out.add(r.t(u), 1 + i, i == 0 ? dz > 0 : dz < 0);
    }
  }
  out.finish(!c.open);
}

STRAHL_HOST_DEVICE inline Vec3 normal_at(const Cone& c, int part, const Vec3& p) {
  if (part == 1) return -c.axis;
  if (part == 2) return c.axis;
  const Vec3 q = p - c.base;
  const Real z = dot(q, c.axis);
  const Vec3 radial = q - c.axis * z;
  const Real len = length(radial);
  if (!(len > 0)) return c.axis;  // the apex
  // ∇(x² + y² − (r0 + k z)²)/2 = radial − (r0 + k z)·k·axis
  const Real k = (c.cap_radius - c.base_radius) / c.height;
  return normalize(radial / len - c.axis * k);
}

STRAHL_HOST_DEVICE inline bool inside(const Cone& c, const Vec3& p) {
  const Vec3 q = p - c.base;
  const Real z = dot(q, c.axis);
  if (!(z > 0 && z < c.height)) return false;
  const Real radius = c.base_radius + (c.cap_radius - c.base_radius) * (z / c.height);
  return length_squared(q - c.axis * z) < radius * radius;
}

}  // namespace strahl::kernel
