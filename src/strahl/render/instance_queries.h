#pragma once
// Scene queries against instances (docs/scene-format.md, "Instances"): a BVH over the instances'
// world boxes at the top; each instance the ray reaches brings the ray into its group's object
// space (geometry/instance.h) and runs the group's own structure there. Two fixed-size stacks,
// no allocation; a scene without instances pays one test of a count.

#include "strahl/geometry/hit.h"
#include "strahl/render/scene_view.h"

namespace strahl {

// One instance's part of the queries below, for a ray in world space (render/moving_shapes.h
// runs them for moving instances, with the ray brought to where the instance stands still).
// The nearest surface of instance x in (t_min, t_far): lowers t_far and sets hit.t, prim, b1 and
// b2 (the caller sets kind and index) when one lies nearer; says whether it did.
STRAHL_HOST_DEVICE inline bool nearest_in_instance(const SceneView& s, const kernel::Instance& x, const Ray& ray,
                                                   Real t_min, Real& t_far, Hit& hit) {
  const kernel::InstanceRay r = kernel::instance_ray(x, ray);
  const NearestHit n = nearest_hit(s.groups[x.group].accel, r.ray, t_min * r.scale, t_far * r.scale);
  if (!(n.hit.t < kInfinity)) return false;
  const Real t = n.hit.t / r.scale;
  if (!(t < t_far && t > t_min)) return false;
  t_far = hit.t = t;
  hit.prim = n.prim;
  hit.b1 = n.hit.b1;
  hit.b2 = n.hit.b2;
  return true;
}

STRAHL_HOST_DEVICE inline bool occluded_in_instance(const SceneView& s, const kernel::Instance& x, const Ray& ray,
                                                    Real t_min, Real t_max) {
  const kernel::InstanceRay r = kernel::instance_ray(x, ray);
  return occluded(s.groups[x.group].accel, r.ray, t_min * r.scale, t_max * r.scale);
}

// Calls cross(material, crossings) for each surface of instance x on (0, t_max); true when it
// stopped the search (cross returned true).
template <class Cross>
STRAHL_HOST_DEVICE inline bool crossings_in_instance(const SceneView& s, const kernel::Instance& x, const Ray& ray,
                                                     Real t_max, Cross& cross) {
  const kernel::InstanceRay r = kernel::instance_ray(x, ray);
  const AccelView& a = s.groups[x.group].accel;
  bool stop = false;
  auto inner = [&](std::uint32_t prim, int n) { return stop = cross(primitive_material(a.prims, prim), n); };
  for_each_crossing(a, r.ray, 0, t_max * r.scale, inner);
  return stop;
}

// Lowers hit.t (and sets the hit) when an instance's surface lies nearer than hit.t.
STRAHL_HOST_DEVICE inline void closest_instance_hit(const SceneView& s, const Ray& ray, Real t_min, Hit& hit) {
  if (s.instance_count == 0) return;
  Real t_max = hit.t;
  auto visit = [&](std::uint32_t i, Real, Real, Real& t_far) {
    if (nearest_in_instance(s, s.instances[i], ray, t_min, t_far, hit)) {
      hit.kind = ShapeKind::Instance;
      hit.index = i;
    }
    return false;
  };
  traverse(s.instance_bvh, ray, t_min, t_max, visit);
}

// Any instance surface in (t_min, t_max)?
STRAHL_HOST_DEVICE inline bool instance_occluded(const SceneView& s, const Ray& ray, Real t_min, Real t_max) {
  if (s.instance_count == 0) return false;
  bool found = false;
  auto visit = [&](std::uint32_t i, Real, Real, Real& t_far) {
    return found = occluded_in_instance(s, s.instances[i], ray, t_min, t_far);
  };
  traverse<false>(s.instance_bvh, ray, t_min, t_max, visit);  // any hit will do: no sorting
  return found;
}

// Calls cross(material, crossings) for every surface of an instance that the segment
// (0, distance) of the shadow ray crosses; stops when it returns true.
template <class Cross>
STRAHL_HOST_DEVICE inline void for_each_instance_crossing(const SceneView& s, const Ray& ray, Real distance, Cross& cross) {
  if (s.instance_count == 0) return;
  Real t_max = distance;
  auto visit = [&](std::uint32_t i, Real, Real, Real& t_far) {
    return crossings_in_instance(s, s.instances[i], ray, t_far, cross);
  };
  traverse(s.instance_bvh, ray, 0, t_max, visit);
}

}  // namespace strahl
