#pragma once
// The surface point of an instance hit (render/surface_point.h's ShapeKind::Instance): the
// primitive's normal found in the group's object space and brought to the world by the inverse
// transpose (geometry/placement.h); the texture coordinate is the object-space point (or a mesh's
// own (u, v)), so a texture moves with the instance (a moving one's too).

#include <cmath>

#include "strahl/geometry/hit.h"
#include "strahl/render/scene_view.h"
#include "strahl/render/triangle_texcoord.h"

namespace strahl {

struct InstanceSurface {
  Vec3 geometric_normal, normal, texcoord;
  std::uint32_t material = 0;
  Real magnitude = 0;  // of the primitive's coordinates in world units (ray offsets)
};

// The surface of instance x at p (world space) for hit.prim, b1, b2; stretch and shift bound the
// group → world map for the offset (x's own, or a moving instance's over the shutter).
STRAHL_HOST_DEVICE inline InstanceSurface instance_surface(const SceneView& s, const kernel::Instance& x, Real stretch,
                                                           Real shift, const Vec3& p, const Hit& hit) {
  const InstanceGroupView& g = s.groups[x.group];
  const PrimitiveSet& prims = g.accel.prims;
  const Vec3 po = kernel::object_point(x.to_object, p);
  InstanceSurface out;
  out.texcoord = po;
  Vec3 geometric, shading;
  Real magnitude = 0;  // object units; 0 for solids, as for solids placed directly
  if (prims.is_sphere(hit.prim)) {
    const kernel::Sphere& sphere = prims.spheres[hit.prim];
    geometric = shading = kernel::normal_at(sphere, po);
    out.material = sphere.material;
    magnitude = max_abs_component(sphere.center) + sphere.radius;
  } else if (prims.is_solid(hit.prim)) {
    const kernel::Solid& solid = prims.solid(hit.prim);
    geometric = shading = kernel::normal_at(prims.shapes, solid, int(hit.b1), po);
    out.material = solid.material;
  } else {
    const kernel::Triangle& tri = prims.triangles[hit.prim - prims.sphere_count];
    geometric = shading = kernel::geometric_normal(tri);
    if (tri.normals >= 0) {
      const kernel::VertexNormals& vn = g.vertex_normals[tri.normals];
      const Vec3 n = vn.n0 * (1 - hit.b1 - hit.b2) + vn.n1 * hit.b1 + vn.n2 * hit.b2;
      if (length_squared(n) > 0) shading = normalize(n);
    }
    out.material = tri.material;
    out.texcoord = triangle_texcoord(s, g.vertex_texcoords, tri.texcoords, tri.material, hit, po);
    magnitude = std::fmax(std::fmax(max_abs_component(tri.v0), max_abs_component(tri.v1)), max_abs_component(tri.v2));
  }
  if (x.translation_only) {
    out.geometric_normal = geometric;
    out.normal = shading;
    out.magnitude = magnitude > 0 ? magnitude + shift : 0;
  } else {
    out.geometric_normal = kernel::world_normal(x.to_object, geometric);
    out.normal = kernel::world_normal(x.to_object, shading);
    out.magnitude = magnitude > 0 ? magnitude * stretch + shift : 0;
  }
  // Keep the shading normal on the geometric normal's side (OBJ normals may disagree).
  if (dot(out.normal, out.geometric_normal) < 0) out.normal = -out.normal;
  return out;
}

STRAHL_HOST_DEVICE inline InstanceSurface instance_surface(const SceneView& s, const Vec3& p, const Hit& hit) {
  const kernel::Instance& x = s.instances[hit.index];
  return instance_surface(s, x, x.stretch, x.shift, p, hit);
}

// A moving instance's at shutter fraction u: found where it stands still (p brought there by
// A(u)⁻¹), the normals brought back by A(u)⁻ᵀ.
STRAHL_HOST_DEVICE inline InstanceSurface moving_instance_surface(const SceneView& s, Real u, const Vec3& p, const Hit& hit) {
  const kernel::MovingInstance& m = s.moving_instances[hit.index];
  const kernel::Placement a = kernel::at_time(m, u);
  InstanceSurface out = instance_surface(s, m.instance, m.stretch, m.shift, kernel::object_point(a, p), hit);
  out.geometric_normal = kernel::world_normal(a, out.geometric_normal);
  out.normal = kernel::world_normal(a, out.normal);
  if (dot(out.normal, out.geometric_normal) < 0) out.normal = -out.normal;
  return out;
}

}  // namespace strahl
