#pragma once
// The solids as the acceleration structures and the renderer see them: nearest hit, crossings
// for shadow rays, normal and inside test of any solid handle, a leaf shape
// (geometry/solid_leaf.h) or a CSG tree (geometry/csg.h), dispatched by kind.

#include "strahl/geometry/csg.h"

namespace strahl::kernel {

// Every crossing of the surface in (t_min, t_max), front to back: calls visit(const
// SolidCrossing&), which returns true to stop.
template <class Visit>
STRAHL_HOST_DEVICE inline void for_each_solid_crossing(const SolidArrays& a, const Solid& s, const Ray& ray,
                                                       Real t_min, Real t_max, Visit&& visit) {
  if (s.kind == SolidKind::Csg) for_each_csg_crossing(a, a.csgs[s.index], ray, t_min, t_max, visit);
  else for_each_leaf_crossing(a, s, ray, t_min, t_max, visit);
}

// The nearest crossing in (t_min, t_max); t = kInfinity when none. Kept out of line: the
// structures' leaf loops call it for their non-triangle lanes only.
STRAHL_HOST_DEVICE STRAHL_NOINLINE inline SolidCrossing intersect(const SolidArrays& a, const Solid& s,
                                                                  const Ray& ray, Real t_min, Real t_max) {
  SolidCrossing first;
  for_each_solid_crossing(a, s, ray, t_min, t_max, [&](const SolidCrossing& c) {
    first = c;
    return true;
  });
  return first;
}

// Is any crossing in (t_min, t_max)? (shadow rays: intersect().t < kInfinity, where an implicit
// leaf need not find which root is the first.)
STRAHL_HOST_DEVICE STRAHL_NOINLINE inline bool any_crossing(const SolidArrays& a, const Solid& s, const Ray& ray,
                                                            Real t_min, Real t_max) {
  if (s.kind != SolidKind::Csg) return leaf_any_crossing(a, s, ray, t_min, t_max);
  return intersect(a, s, ray, t_min, t_max).t < kInfinity;
}

// How many times (t_min, t_max) crosses the surface.
STRAHL_HOST_DEVICE STRAHL_NOINLINE inline int crossings(const SolidArrays& a, const Solid& s, const Ray& ray,
                                                        Real t_min, Real t_max) {
  int n = 0;
  for_each_solid_crossing(a, s, ray, t_min, t_max, [&](const SolidCrossing&) {
    ++n;
    return false;
  });
  return n;
}

// Outward unit normal at a surface point of part `part`.
STRAHL_HOST_DEVICE inline Vec3 normal_at(const SolidArrays& a, const Solid& s, int part, const Vec3& p) {
  if (s.kind == SolidKind::Csg) return csg_normal_at(a, a.csgs[s.index], std::uint32_t(part), p);
  return leaf_normal_at(a, s, part, p);
}

// Is p inside the solid? (false for open surfaces: disks, open cones, clipped quadrics are not
// solids; a clipped quadric answers for its clipped region.)
STRAHL_HOST_DEVICE inline bool inside(const SolidArrays& a, const Solid& s, const Vec3& p) {
  if (s.kind == SolidKind::Csg) return csg_inside(a, a.csgs[s.index], p);
  return leaf_inside(a, s, p);
}

}  // namespace strahl::kernel
