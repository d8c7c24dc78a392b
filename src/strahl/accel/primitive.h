#pragma once
// Bounded primitives as acceleration structures see them: one id space over all spheres and
// triangles (ids below sphere_count are spheres, the rest triangles). Planes are unbounded and
// stay outside every structure.

#include <cstdint>

#include "strahl/geometry/sphere.h"
#include "strahl/geometry/triangle.h"
#include "strahl/math/bounds.h"

namespace strahl {

struct PrimitiveSet {
  const kernel::Sphere* spheres = nullptr;
  std::uint32_t sphere_count = 0;
  const kernel::Triangle* triangles = nullptr;
  std::uint32_t triangle_count = 0;

  STRAHL_HOST_DEVICE std::uint32_t size() const { return sphere_count + triangle_count; }
  STRAHL_HOST_DEVICE bool is_sphere(std::uint32_t prim) const { return prim < sphere_count; }
};

STRAHL_HOST_DEVICE inline Bounds primitive_bounds(const PrimitiveSet& p, std::uint32_t prim) {
  Bounds b;
  if (p.is_sphere(prim)) {
    const kernel::Sphere& s = p.spheres[prim];
    b.extend(s.center - Vec3(s.radius));
    b.extend(s.center + Vec3(s.radius));
  } else {
    const kernel::Triangle& t = p.triangles[prim - p.sphere_count];
    b.extend(t.v0);
    b.extend(t.v1);
    b.extend(t.v2);
  }
  return b;
}

// Nearest root of one primitive in (t_min, t_max); triangles also give barycentrics. `shear` is
// kernel::ray_shear(ray.direction), computed once per ray.
STRAHL_HOST_DEVICE inline kernel::TriangleHit intersect_primitive(const PrimitiveSet& p, std::uint32_t prim,
                                                                  const Ray& ray, const kernel::RayShear& shear,
                                                                  Real t_min, Real t_max) {
  if (p.is_sphere(prim)) return {kernel::intersect(p.spheres[prim], ray, t_min, t_max), 0, 0};
  return kernel::intersect(p.triangles[prim - p.sphere_count], ray, shear, t_min, t_max);
}
STRAHL_HOST_DEVICE inline kernel::TriangleHit intersect_primitive(const PrimitiveSet& p, std::uint32_t prim,
                                                                  const Ray& ray, Real t_min, Real t_max) {
  return intersect_primitive(p, prim, ray, kernel::ray_shear(ray.direction), t_min, t_max);
}

STRAHL_HOST_DEVICE inline std::uint32_t primitive_material(const PrimitiveSet& p, std::uint32_t prim) {
  return p.is_sphere(prim) ? p.spheres[prim].material : p.triangles[prim - p.sphere_count].material;
}

// How often the segment (t_min, t_max) crosses the primitive's surface (0..2).
STRAHL_HOST_DEVICE inline int primitive_crossings(const PrimitiveSet& p, std::uint32_t prim, const Ray& ray,
                                                  const kernel::RayShear& shear, Real t_min, Real t_max) {
  if (p.is_sphere(prim)) return kernel::crossings(p.spheres[prim], ray, t_min, t_max);
  return kernel::intersect(p.triangles[prim - p.sphere_count], ray, shear, t_min, t_max).t < kInfinity ? 1 : 0;
}
STRAHL_HOST_DEVICE inline int primitive_crossings(const PrimitiveSet& p, std::uint32_t prim, const Ray& ray,
                                                  Real t_min, Real t_max) {
  return primitive_crossings(p, prim, ray, kernel::ray_shear(ray.direction), t_min, t_max);
}

}  // namespace strahl
