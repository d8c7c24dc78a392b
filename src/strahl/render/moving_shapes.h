#pragma once
// Scene queries against the moving shapes (motion blur): each is intersected where it is at the
// ray's time (a solid or an instance: the ray brought to where it stands still,
// geometry/moving_map.h). They sit in BVHs of their own over their swept boxes, one per time
// segment of the shutter (accel/motion_bvh.h), so static shapes keep their tight tree and a
// static scene pays nothing (an empty tree is skipped at once).

#include "strahl/geometry/hit.h"
#include "strahl/render/instance_queries.h"
#include "strahl/render/scene_view.h"

namespace strahl {

// The ray's time as a fraction u ∈ [0, 1] of the shutter interval.
STRAHL_HOST_DEVICE inline Real shutter_fraction(const SceneView& s, Real time) {
  const Real u = (time - s.shutter_open) * s.inv_shutter;
  return u < 0 ? Real(0) : (u > 1 ? Real(1) : u);
}

// Lowers hit.t (and sets the hit) when a moving shape lies nearer than hit.t.
STRAHL_HOST_DEVICE inline void closest_moving_hit(const SceneView& s, const Ray& ray, Real t_min, Hit& hit) {
  if (s.moving_count() == 0) return;
  const Real u = shutter_fraction(s, ray.time);
  Real t_max = hit.t;
  auto visit = [&](std::uint32_t prim, Real, Real, Real& t_far) {
    if (prim < s.moving_sphere_count) {
      const Real t = kernel::intersect(kernel::at_time(s.moving_spheres[prim], u), ray, t_min, t_far);
      if (t < t_far) {
        t_far = hit.t = t;
        hit.kind = ShapeKind::MovingSphere;
        hit.index = prim;
      }
    } else if (prim < s.moving_sphere_count + s.moving_triangle_count) {
      const std::uint32_t i = prim - s.moving_sphere_count;
      const kernel::MovingTriangleHit h = kernel::intersect(kernel::at_time(s.moving_triangles[i], u), ray, t_min, t_far);
      if (h.t < t_far) {
        t_far = hit.t = h.t;
        hit.kind = ShapeKind::MovingTriangle;
        hit.index = i;
        hit.b1 = h.b1;
        hit.b2 = h.b2;
      }
    } else if (prim < s.moving_sphere_count + s.moving_triangle_count + s.moving_solid_count) {
      const std::uint32_t i = prim - s.moving_sphere_count - s.moving_triangle_count;
      const kernel::MovingSolid& ms = s.moving_solids[i];
      const Ray r = kernel::object_ray(kernel::at_time(ms, u), ray);
      const kernel::SolidCrossing c = kernel::intersect(s.accel.prims.shapes, ms.solid, r, t_min, t_far);
      if (c.t < t_far) {
        t_far = hit.t = c.t;
        hit.kind = ShapeKind::MovingSolid;
        hit.index = i;
        hit.b1 = Real(c.part);
      }
    } else {
      const std::uint32_t i = prim - s.moving_sphere_count - s.moving_triangle_count - s.moving_solid_count;
      const kernel::MovingInstance& mi = s.moving_instances[i];
      if (nearest_in_instance(s, mi.instance, kernel::object_ray(kernel::at_time(mi, u), ray), t_min, t_far, hit)) {
        hit.kind = ShapeKind::MovingInstance;
        hit.index = i;
      }
    }
    return false;
  };
  traverse(s.moving_bvh.segment_at(u), ray, t_min, t_max, visit);
}

// Calls cross(material, crossings) for every moving shape the segment (0, distance) of the
// shadow ray crosses; stops when it returns true. kNearestFirst: the shapes in the order of
// their boxes along the ray; else in the tree's order (any-hit queries: no sorting).
template <bool kNearestFirst = true, class Cross>
STRAHL_HOST_DEVICE inline void for_each_moving_crossing(const SceneView& s, const Ray& ray, Real distance, Cross& cross) {
  if (s.moving_count() == 0) return;
  const Real u = shutter_fraction(s, ray.time);
  Real t_max = distance;
  auto visit = [&](std::uint32_t prim, Real, Real, Real& t_far) {
    if (prim < s.moving_sphere_count) {
      const kernel::MovingSphere& ms = s.moving_spheres[prim];
      const int n = kernel::crossings(kernel::at_time(ms, u), ray, 0, t_far);
      return n > 0 && cross(ms.material, n);
    }
    if (prim < s.moving_sphere_count + s.moving_triangle_count) {
      const kernel::MovingTriangle& mt = s.moving_triangles[prim - s.moving_sphere_count];
      return kernel::intersect(kernel::at_time(mt, u), ray, 0, t_far).t < kInfinity && cross(mt.material, 1);
    }
    const std::uint32_t i = prim - s.moving_sphere_count - s.moving_triangle_count;
    if (i < s.moving_solid_count) {
      const kernel::MovingSolid& ms = s.moving_solids[i];
      const Ray r = kernel::object_ray(kernel::at_time(ms, u), ray);
      const int n = kernel::crossings(s.accel.prims.shapes, ms.solid, r, 0, t_far);
      return n > 0 && cross(ms.solid.material, n);
    }
    const kernel::MovingInstance& mi = s.moving_instances[i - s.moving_solid_count];
    return crossings_in_instance(s, mi.instance, kernel::object_ray(kernel::at_time(mi, u), ray), t_far, cross);
  };
  traverse<kNearestFirst>(s.moving_bvh.segment_at(u), ray, 0, t_max, visit);
}

// Does a moving shape lie on the segment (0, distance) of the shadow ray? The any-hit query of
// scenes with nothing transparent.
STRAHL_HOST_DEVICE inline bool moving_occluded(const SceneView& s, const Ray& ray, Real distance) {
  bool blocked = false;
  auto stop = [&](std::uint32_t, int) { return blocked = true; };
  for_each_moving_crossing<false>(s, ray, distance, stop);
  return blocked;
}

}  // namespace strahl
