#pragma once
// The lecture's nearest-intersection search over all objects (n_x · n_y · n_o tests), and the
// shadow-ray query. Meshes are skipped as a whole when the ray misses their bounds.

#include "strahl/geometry/hit.h"
#include "strahl/render/scene_view.h"

namespace strahl {

STRAHL_HOST_DEVICE inline Vec3 reciprocal(const Vec3& d) { return {Real(1) / d.x, Real(1) / d.y, Real(1) / d.z}; }

// Nearest hit in (t_min, t_max).
STRAHL_HOST_DEVICE inline Hit closest_hit(const SceneView& s, const Ray& ray, Real t_min, Real t_max) {
  Hit hit;
  hit.t = t_max;
  for (std::uint32_t i = 0; i < s.sphere_count; ++i) {
    const Real t = kernel::intersect(s.spheres[i], ray, t_min, hit.t);
    if (t < hit.t) { hit.t = t; hit.kind = ShapeKind::Sphere; hit.index = i; }
  }
  for (std::uint32_t i = 0; i < s.plane_count; ++i) {
    const Real t = kernel::intersect(s.planes[i], ray, t_min, hit.t);
    if (t < hit.t) { hit.t = t; hit.kind = ShapeKind::Plane; hit.index = i; }
  }
  if (s.mesh_count > 0) {
    const Vec3 inv_dir = reciprocal(ray.direction);
    for (std::uint32_t m = 0; m < s.mesh_count; ++m) {
      const MeshRange& mesh = s.meshes[m];
      if (!hits(mesh.bounds, ray.origin, inv_dir, t_min, hit.t)) continue;
      for (std::uint32_t i = mesh.first; i < mesh.first + mesh.count; ++i) {
        const kernel::TriangleHit th = kernel::intersect(s.triangles[i], ray, t_min, hit.t);
        if (th.t < hit.t) { hit.t = th.t; hit.kind = ShapeKind::Triangle; hit.index = i; hit.b1 = th.b1; hit.b2 = th.b2; }
      }
    }
  }
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
STRAHL_HOST_DEVICE inline Vec3 transmittance(const SceneView& s, const Ray& ray, Real distance) {
  Vec3 tr{1};
  for (std::uint32_t i = 0; i < s.sphere_count; ++i) {
    for (int k = kernel::crossings(s.spheres[i], ray, 0, distance); k > 0; --k)
      if (!attenuate(s.materials[s.spheres[i].material], tr)) return Vec3(0);
  }
  for (std::uint32_t i = 0; i < s.plane_count; ++i) {
    if (kernel::intersect(s.planes[i], ray, 0, distance) < kInfinity &&
        !attenuate(s.materials[s.planes[i].material], tr))
      return Vec3(0);
  }
  if (s.mesh_count > 0) {
    const Vec3 inv_dir = reciprocal(ray.direction);
    for (std::uint32_t m = 0; m < s.mesh_count; ++m) {
      const MeshRange& mesh = s.meshes[m];
      if (!hits(mesh.bounds, ray.origin, inv_dir, 0, distance)) continue;
      for (std::uint32_t i = mesh.first; i < mesh.first + mesh.count; ++i) {
        if (kernel::intersect(s.triangles[i], ray, 0, distance).t < kInfinity &&
            !attenuate(s.materials[s.triangles[i].material], tr))
          return Vec3(0);
      }
    }
  }
  return tr;
}

}  // namespace strahl
