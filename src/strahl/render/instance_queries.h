#pragma once
// Scene queries against instances (docs/scene-format.md, "Instances"): a BVH over the instances'
// world boxes at the top; each instance the ray reaches brings the ray into its group's object
// space (geometry/instance.h) and runs the group's own structure there. Two fixed-size stacks,
// no allocation; a scene without instances pays one test of a count.

#include "strahl/geometry/hit.h"
#include "strahl/render/scene_view.h"

namespace strahl {

// Lowers hit.t (and sets the hit) when an instance's surface lies nearer than hit.t.
STRAHL_HOST_DEVICE inline void closest_instance_hit(const SceneView& s, const Ray& ray, Real t_min, Hit& hit) {
  if (s.instance_count == 0) return;
  Real t_max = hit.t;
  auto visit = [&](std::uint32_t i, Real, Real, Real& t_far) {
    const kernel::Instance& x = s.instances[i];
    const kernel::InstanceRay r = kernel::instance_ray(x, ray);
    const NearestHit n = nearest_hit(s.groups[x.group].accel, r.ray, t_min * r.scale, t_far * r.scale);
    if (n.hit.t < kInfinity) {
      const Real t = n.hit.t / r.scale;
      if (t < t_far && t > t_min) {
        t_far = hit.t = t;
        hit.kind = ShapeKind::Instance;
        hit.index = i;
        hit.prim = n.prim;
        hit.b1 = n.hit.b1;
        hit.b2 = n.hit.b2;
      }
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
    const kernel::Instance& x = s.instances[i];
    const kernel::InstanceRay r = kernel::instance_ray(x, ray);
    found = occluded(s.groups[x.group].accel, r.ray, t_min * r.scale, t_far * r.scale);
    return found;
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
    const kernel::Instance& x = s.instances[i];
    const kernel::InstanceRay r = kernel::instance_ray(x, ray);
    const AccelView& a = s.groups[x.group].accel;
    bool stop = false;
    auto inner = [&](std::uint32_t prim, int n) { return stop = cross(primitive_material(a.prims, prim), n); };
    for_each_crossing(a, r.ray, 0, t_far * r.scale, inner);
    return stop;
  };
  traverse(s.instance_bvh, ray, 0, t_max, visit);
}

}  // namespace strahl
