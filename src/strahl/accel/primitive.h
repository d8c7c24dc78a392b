#pragma once
// Bounded primitives as acceleration structures see them: one id space over spheres, triangles
// and solids (DESIGN.md "Every bounded shape in one primitive set"): ids below sphere_count are
// spheres, the next triangle_count triangles, the rest solids (geometry/solid.h: boxes, cones,
// tori, clipped quadrics, implicit surfaces…, dispatched by kind). Planes and unbounded quadrics
// stay outside every structure. Solids come last so that the triangle ids and the structures'
// triangle blocks stay as they were; a leaf holds spheres and solids in its blocks' `other`
// lanes, tested from these arrays.

#include <cstdint>

#include "strahl/geometry/solid.h"
#include "strahl/geometry/sphere.h"
#include "strahl/geometry/triangle.h"
#include "strahl/math/bounds.h"

namespace strahl {

struct PrimitiveSet {
  const kernel::Sphere* spheres = nullptr;
  std::uint32_t sphere_count = 0;
  const kernel::Triangle* triangles = nullptr;
  std::uint32_t triangle_count = 0;
  const kernel::Solid* solids = nullptr;
  std::uint32_t solid_count = 0;
  kernel::SolidArrays shapes;  // what the solids' handles index

  STRAHL_HOST_DEVICE std::uint32_t size() const { return sphere_count + triangle_count + solid_count; }
  STRAHL_HOST_DEVICE bool is_sphere(std::uint32_t prim) const { return prim < sphere_count; }
  STRAHL_HOST_DEVICE std::uint32_t first_solid() const { return sphere_count + triangle_count; }
  STRAHL_HOST_DEVICE bool is_solid(std::uint32_t prim) const { return prim >= first_solid(); }
  STRAHL_HOST_DEVICE bool is_triangle(std::uint32_t prim) const { return !is_sphere(prim) && !is_solid(prim); }
  STRAHL_HOST_DEVICE const kernel::Solid& solid(std::uint32_t prim) const { return solids[prim - first_solid()]; }
};

// A non-triangle primitive's nearest hit (the structures' `other` lanes): a sphere's root, or a
// solid's crossing with its part in b1.
STRAHL_HOST_DEVICE inline kernel::TriangleHit intersect_other(const PrimitiveSet& p, std::uint32_t prim,
                                                              const Ray& ray, Real t_min, Real t_max) {
  if (p.is_sphere(prim)) return {kernel::intersect(p.spheres[prim], ray, t_min, t_max), 0, 0};
  const kernel::SolidCrossing c = kernel::intersect(p.shapes, p.solid(prim), ray, t_min, t_max);
  return {c.t, Real(c.part), 0};
}

// Does a non-triangle primitive have any hit in (t_min, t_max)? (any-hit queries: a solid need
// not find which of its crossings is the nearest.)
STRAHL_HOST_DEVICE inline bool hits_other(const PrimitiveSet& p, std::uint32_t prim, const Ray& ray, Real t_min,
                                          Real t_max) {
  if (p.is_sphere(prim)) return kernel::intersect(p.spheres[prim], ray, t_min, t_max) < kInfinity;
  return kernel::any_crossing(p.shapes, p.solid(prim), ray, t_min, t_max);
}

STRAHL_HOST_DEVICE inline Bounds primitive_bounds(const PrimitiveSet& p, std::uint32_t prim) {
  Bounds b;
  if (p.is_sphere(prim)) {
    const kernel::Sphere& s = p.spheres[prim];
    b.extend(s.center - Vec3(s.radius));
    b.extend(s.center + Vec3(s.radius));
  } else if (p.is_solid(prim)) {
    b = kernel::bounds(p.shapes, p.solid(prim));
  } else {
    const kernel::Triangle& t = p.triangles[prim - p.sphere_count];
    b.extend(t.v0);
    b.extend(t.v1);
    b.extend(t.v2);
  }
  return b;
}

// The ray's shear for the watertight triangle test (kernel::ray_shear: three divisions), or a
// placeholder when the set has no triangles, whose tests are then never run.
STRAHL_HOST_DEVICE inline kernel::RayShear ray_shear_for(const PrimitiveSet& p, const Vec3& direction) {
  return p.triangle_count > 0 ? kernel::ray_shear(direction) : kernel::RayShear{};
}

// Nearest root of one primitive in (t_min, t_max); triangles also give barycentrics. `shear` is
// ray_shear_for(p, ray.direction), computed once per ray.
STRAHL_HOST_DEVICE inline kernel::TriangleHit intersect_primitive(const PrimitiveSet& p, std::uint32_t prim,
                                                                  const Ray& ray, const kernel::RayShear& shear,
                                                                  Real t_min, Real t_max) {
  if (p.is_triangle(prim)) return kernel::intersect(p.triangles[prim - p.sphere_count], ray, shear, t_min, t_max);
  return intersect_other(p, prim, ray, t_min, t_max);
}
STRAHL_HOST_DEVICE inline kernel::TriangleHit intersect_primitive(const PrimitiveSet& p, std::uint32_t prim,
                                                                  const Ray& ray, Real t_min, Real t_max) {
  return intersect_primitive(p, prim, ray, ray_shear_for(p, ray.direction), t_min, t_max);
}

STRAHL_HOST_DEVICE inline std::uint32_t primitive_material(const PrimitiveSet& p, std::uint32_t prim) {
  if (p.is_sphere(prim)) return p.spheres[prim].material;
  if (p.is_solid(prim)) return p.solid(prim).material;
  return p.triangles[prim - p.sphere_count].material;
}

// How often the segment (t_min, t_max) crosses the primitive's surface (a sphere 0..2, a torus
// up to 4, an implicit surface any number).
STRAHL_HOST_DEVICE inline int primitive_crossings(const PrimitiveSet& p, std::uint32_t prim, const Ray& ray,
                                                  const kernel::RayShear& shear, Real t_min, Real t_max) {
  if (p.is_sphere(prim)) return kernel::crossings(p.spheres[prim], ray, t_min, t_max);
  if (p.is_solid(prim)) return kernel::crossings(p.shapes, p.solid(prim), ray, t_min, t_max);
  return kernel::intersect(p.triangles[prim - p.sphere_count], ray, shear, t_min, t_max).t < kInfinity ? 1 : 0;
}
STRAHL_HOST_DEVICE inline int primitive_crossings(const PrimitiveSet& p, std::uint32_t prim, const Ray& ray,
                                                  Real t_min, Real t_max) {
  return primitive_crossings(p, prim, ray, ray_shear_for(p, ray.direction), t_min, t_max);
}

}  // namespace strahl
