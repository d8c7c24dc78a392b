#pragma once
// Scene queries: the nearest intersection (lecture 2.1) and the light a shadow ray lets through
// (2.3). Spheres, triangles and bounded solids go through the acceleration structure, planes and
// unbounded solids are tested one by one.

#include "strahl/geometry/hit.h"
#include "strahl/render/instance_queries.h"
#include "strahl/render/moving_shapes.h"
#include "strahl/render/scene_view.h"

namespace strahl {

// Nearest hit in (t_min, t_max).
STRAHL_HOST_DEVICE inline Hit closest_hit(const SceneView& s, const Ray& ray, Real t_min, Real t_max) {
  Hit hit;
  hit.t = t_max;
  for (std::uint32_t i = 0; i < s.plane_count; ++i) {
    const Real t = kernel::intersect(s.planes[i], ray, t_min, hit.t);
    if (t < hit.t) { hit.t = t; hit.kind = ShapeKind::Plane; hit.index = i; }
  }
  for (std::uint32_t i = s.bounded_solid_count; i < s.solid_count; ++i) {
    const kernel::SolidCrossing c = kernel::intersect(s.accel.prims.shapes, s.solids[i], ray, t_min, hit.t);
    if (c.t < hit.t) { hit.t = c.t; hit.kind = ShapeKind::Solid; hit.index = i; hit.b1 = c.part; }
  }
  const NearestHit nearest = is_sphere_leaf(s.accel) ? sphere_leaf_nearest(s.accel, ray, t_min, hit.t)
                                                     : nearest_hit(s.accel, ray, t_min, hit.t);
  if (nearest.hit.t < hit.t) {
    hit.t = nearest.hit.t;
    if (s.accel.prims.is_sphere(nearest.prim)) {
      hit.kind = ShapeKind::Sphere;
      hit.index = nearest.prim;
    } else if (s.accel.prims.is_solid(nearest.prim)) {
      hit.kind = ShapeKind::Solid;
      hit.index = nearest.prim - s.accel.prims.first_solid();
      hit.b1 = nearest.hit.b1;
    } else {
      hit.kind = ShapeKind::Triangle;
      hit.index = nearest.prim - s.accel.prims.sphere_count;
      hit.b1 = nearest.hit.b1;
      hit.b2 = nearest.hit.b2;
    }
  }
  // Each guarded here as well as inside: a scene without moving shapes or instances pays no call.
  if (s.moving_count() > 0) closest_moving_hit(s, ray, t_min, hit);
  if (s.instance_count > 0) closest_instance_hit(s, ray, t_min, hit);
  if (!hit.found()) hit.t = kInfinity;
  return hit;
}

// What one crossing of an occluder's surface lets through of the light: nothing when opaque,
// its transparency (tinted by its colour when it filters) when transparent. A shadow ray crossing
// a sphere or a closed mesh passes two surfaces and is attenuated twice (as POV-Ray does).
STRAHL_HOST_DEVICE inline bool attenuate(const Material& m, Vec3& transmittance) {
  if (m.transparency <= 0) return false;
  transmittance = transmittance * (m.filter ? m.color * m.transparency : Vec3(m.transparency));
  return true;
}

// Light reaching a point along a shadow ray of length `distance` (a unit ray towards the light):
// 0 when an opaque surface lies in between, the product of the crossings' transmittances otherwise.
STRAHL_HOST_DEVICE STRAHL_DEVICE_NOINLINE Vec3 transmittance(const SceneView& s, const Ray& ray, Real distance) {
  Vec3 tr{1};
  for (std::uint32_t i = 0; i < s.plane_count; ++i) {
    if (kernel::intersect(s.planes[i], ray, 0, distance) < kInfinity &&
        !attenuate(s.materials[s.planes[i].material], tr))
      return Vec3(0);
  }
  for (std::uint32_t i = s.bounded_solid_count; i < s.solid_count; ++i) {
    const int n = kernel::crossings(s.accel.prims.shapes, s.solids[i], ray, 0, distance);
    for (int k = 0; k < n; ++k)
      if (!attenuate(s.materials[s.solids[i].material], tr)) return Vec3(0);
  }
  // Nothing transparent: the first surface found blocks the light (any-hit, no crossings to count).
  if (s.opaque) {
    const bool blocked = is_sphere_leaf(s.accel) ? sphere_leaf_occluded(s.accel, ray, 0, distance)
                                                 : occluded(s.accel, ray, 0, distance);
    return blocked || (s.instance_count > 0 && instance_occluded(s, ray, 0, distance)) ||
                   moving_occluded(s, ray, distance)
               ? Vec3(0)
               : tr;
  }
  if (is_sphere_leaf(s.accel) && s.moving_count() == 0 && s.instance_count == 0) {
    // One leaf of spheres: for_each_crossing's naive loop, without its visitor.
    if (s.accel.sphere_quads != nullptr) {
      const std::uint32_t quads = kernel::sphere_quad_count(s.accel.prims.sphere_count);
      for (std::uint32_t j = 0; j < quads; ++j) {
        int n[kernel::kSphereQuadWidth];
        kernel::crossings(s.accel.sphere_quads[j], ray, 0, distance, n);
        for (int k = 0; k < kernel::kSphereQuadWidth; ++k)
          for (int c = 0; c < n[k]; ++c)
            if (!attenuate(s.materials[s.accel.prims.spheres[j * kernel::kSphereQuadWidth + std::uint32_t(k)].material], tr))
              return Vec3(0);
      }
      return tr;
    }
    for (std::uint32_t i = 0; i < s.accel.prims.sphere_count; ++i) {
      const kernel::Sphere& sphere = s.accel.prims.spheres[i];
      const int n = kernel::crossings(sphere, ray, 0, distance);
      for (int k = 0; k < n; ++k)
        if (!attenuate(s.materials[sphere.material], tr)) return Vec3(0);
    }
    return tr;
  }
  bool blocked = false;
  auto cross = [&](std::uint32_t prim, int crossings) {
    const Material& m = s.materials[primitive_material(s.accel.prims, prim)];
    for (int k = 0; k < crossings; ++k) {
      if (!attenuate(m, tr)) {
        blocked = true;
        return true;  // opaque: stop looking
      }
    }
    return false;
  };
  for_each_crossing(s.accel, ray, 0, distance, cross);
  if (blocked) return Vec3(0);
  auto cross_moving = [&](std::uint32_t material, int crossings) {
    for (int k = 0; k < crossings; ++k)
      if (!attenuate(s.materials[material], tr)) return blocked = true;
    return false;
  };
  for_each_moving_crossing(s, ray, distance, cross_moving);
  if (!blocked) for_each_instance_crossing(s, ray, distance, cross_moving);
  return blocked ? Vec3(0) : tr;
}

}  // namespace strahl
