#pragma once
// Everything shading needs about the nearest hit, derived once from the Hit record.

#include "strahl/geometry/hit.h"
#include "strahl/render/scene_view.h"

namespace strahl {

struct SurfacePoint {
  Vec3 p;                // the hit point
  Vec3 geometric_normal; // outward (sphere), the plane's N, or by the triangle's winding
  Vec3 normal;           // shading normal: interpolated vertex normals, else the geometric one
  Vec3 texcoord;         // plane (u, v, 0) or the point itself, for procedural textures
  std::uint32_t material = 0;
};

STRAHL_HOST_DEVICE inline SurfacePoint surface_at(const SceneView& s, const Ray& ray, const Hit& hit) {
  SurfacePoint sp;
  sp.p = ray.at(hit.t);
  switch (hit.kind) {
    case ShapeKind::Sphere: {
      const kernel::Sphere& sphere = s.spheres[hit.index];
      sp.geometric_normal = sp.normal = kernel::normal_at(sphere, sp.p);
      sp.texcoord = sp.p;
      sp.material = sphere.material;
      break;
    }
    case ShapeKind::Plane: {
      const kernel::Plane& plane = s.planes[hit.index];
      sp.geometric_normal = sp.normal = plane.normal;
      sp.texcoord = Vec3(dot(sp.p, plane.tangent), dot(sp.p, plane.bitangent), 0);
      sp.material = plane.material;
      break;
    }
    case ShapeKind::Triangle: {
      const kernel::Triangle& tri = s.triangles[hit.index];
      sp.geometric_normal = kernel::geometric_normal(tri);
      sp.normal = sp.geometric_normal;
      if (tri.normals >= 0) {
        const kernel::VertexNormals& vn = s.vertex_normals[tri.normals];
        const Vec3 n = vn.n0 * (1 - hit.b1 - hit.b2) + vn.n1 * hit.b1 + vn.n2 * hit.b2;
        if (length_squared(n) > 0) sp.normal = normalize(n);
        // Keep the shading normal on the geometric normal's side (OBJ normals may disagree).
        if (dot(sp.normal, sp.geometric_normal) < 0) sp.normal = -sp.normal;
      }
      sp.texcoord = sp.p;
      sp.material = tri.material;
      break;
    }
    case ShapeKind::None: break;
  }
  return sp;
}

}  // namespace strahl
