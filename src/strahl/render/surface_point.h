#pragma once
// Everything shading needs about the nearest hit, derived once from the Hit record.

#include <cmath>

#include "strahl/geometry/hit.h"
#include "strahl/render/instance_surface.h"
#include "strahl/render/moving_shapes.h"
#include "strahl/render/scene_view.h"

namespace strahl {

struct SurfacePoint {
  Vec3 p;                // the hit point
  Vec3 geometric_normal; // outward (sphere), the plane's N, or by the triangle's winding
  Vec3 normal;           // shading normal: interpolated vertex normals, else the geometric one
  Vec3 texcoord;         // the point itself (an instance's: in its group's space), a checkered plane's (u, v, 0),
                         // a mesh's (u, v, 0) under a uv-mapped image
  std::uint32_t material = 0;
  Real time = 0;         // the ray's time (motion blur): secondary rays keep it
  Real offset = 0;       // how far secondary rays start off the surface (a bound on p's error)
};

// The larger of a and b, where b is not NaN: std::fmax's answer (b also where a is NaN) without
// the call to libm's fmax that GCC makes for it.
STRAHL_HOST_DEVICE constexpr Real larger_of(Real a, Real b) { return a > b ? a : b; }

// Largest coordinate magnitude of a triangle's vertices (finite: the scene's).
STRAHL_HOST_DEVICE inline Real vertex_magnitude(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Real ab = larger_of(max_abs_component(a), max_abs_component(b));
  return larger_of(ab, max_abs_component(c));
}

// The offset of secondary rays from a hit point p: it must exceed the rounding error of p and
// of the next intersection test with the same primitive, both of which scale with the magnitudes
// involved — p's coordinates, the primitive's (`magnitude`: |centre| + radius, the vertices, |d|)
// and the path o + t·d that found p — and with nothing absolute, so that scaling a scene by any
// factor in the supported range (docs/scene-format.md, "Units and scale") scales the offsets too.
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE Real ray_offset(const Ray& ray, Real t, const Vec3& p, Real magnitude) {
  return kRayEpsilon * larger_of(max_abs_component(p), magnitude) +  // (magnitude: finite)
         kRayPathEpsilon * (max_abs_component(ray.origin) + t);
}

// Storage for a SurfacePoint that surface_at fills field by field: without the zeroing of its
// 13 members (a `rep stos` per hit, ~2 % of the lecture scene's render time).
union SurfacePointSlot {
  SurfacePoint sp;
  STRAHL_HOST_DEVICE SurfacePointSlot() {}
};

// The surface point of `hit` on `ray`, written into `sp` (where it is to be kept: a copy of a
// SurfacePoint just written field by field stalls on store forwarding).
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void surface_at(const SceneView& s, const Ray& ray, const Hit& hit, SurfacePoint& sp) {
  sp.p = ray.at(hit.t);
  sp.time = ray.time;
  // Every kind sets the normals, texcoord, material and offset below (kinds that know their own
  // magnitude pass it to ray_offset; the others use 0, computed only for them).
  switch (hit.kind) {
    case ShapeKind::Sphere: {
      const kernel::Sphere& sphere = s.spheres[hit.index];
      sp.geometric_normal = sp.normal = kernel::normal_at(sphere, sp.p);
      sp.texcoord = sp.p;
      sp.material = sphere.material;
      sp.offset = ray_offset(ray, hit.t, sp.p, max_abs_component(sphere.center) + sphere.radius);
      break;
    }
    case ShapeKind::Plane: {
      const kernel::Plane& plane = s.planes[hit.index];
      sp.geometric_normal = sp.normal = plane.normal;
      // The checker's squares in the plane's own (u, v); an image is read at the point, as on
      // every other shape (and as POV-Ray reads it).
      sp.texcoord = s.materials[plane.material].texture != kNoTexture
                        ? sp.p
                        : Vec3(dot(sp.p, plane.tangent), dot(sp.p, plane.bitangent), 0);
      sp.material = plane.material;
      sp.offset = ray_offset(ray, hit.t, sp.p, std::fabs(plane.distance));
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
      sp.texcoord = triangle_texcoord(s, s.vertex_texcoords, tri.texcoords, tri.material, hit, sp.p);
      sp.material = tri.material;
      sp.offset = ray_offset(ray, hit.t, sp.p, vertex_magnitude(tri.v0, tri.v1, tri.v2));
      break;
    }
    case ShapeKind::MovingSphere: {
      const kernel::MovingSphere& ms = s.moving_spheres[hit.index];
      const kernel::Sphere sphere = kernel::at_time(ms, shutter_fraction(s, ray.time));
      sp.geometric_normal = sp.normal = kernel::normal_at(sphere, sp.p);
      sp.texcoord = sp.p;
      sp.material = ms.material;
      sp.offset = ray_offset(ray, hit.t, sp.p, max_abs_component(sphere.center) + sphere.radius);
      break;
    }
    case ShapeKind::MovingTriangle: {
      const kernel::MovingTriangle& mt = s.moving_triangles[hit.index];
      const Real u = shutter_fraction(s, ray.time);
      const kernel::TriangleAtTime tri = kernel::at_time(mt, u);
      sp.geometric_normal = sp.normal = kernel::geometric_normal(tri);
      sp.offset = ray_offset(ray, hit.t, sp.p, vertex_magnitude(tri.a, tri.b, tri.c));
      if (mt.normals >= 0) {
        const kernel::VertexNormals& a = s.vertex_normals[mt.normals];
        const kernel::VertexNormals& b = s.vertex_normals[mt.normals + 1];
        const Real w0 = 1 - hit.b1 - hit.b2;
        const Vec3 n = kernel::lerp(a.n0, b.n0, u) * w0 + kernel::lerp(a.n1, b.n1, u) * hit.b1 +
                       kernel::lerp(a.n2, b.n2, u) * hit.b2;
        if (length_squared(n) > 0) sp.normal = normalize(n);
        if (dot(sp.normal, sp.geometric_normal) < 0) sp.normal = -sp.normal;
      }
      sp.texcoord = triangle_texcoord(s, s.vertex_texcoords, mt.texcoords, mt.material, hit, sp.p);
      sp.material = mt.material;
      break;
    }
    case ShapeKind::Solid: {
      const kernel::Solid& solid = s.solids[hit.index];
      sp.geometric_normal = sp.normal = kernel::normal_at(s.accel.prims.shapes, solid, int(hit.b1), sp.p);
      sp.texcoord = sp.p;
      sp.material = solid.material;
      sp.offset = ray_offset(ray, hit.t, sp.p, 0);
      break;
    }
    case ShapeKind::MovingSolid: {
      // The normal where the solid is unmoved, brought back by A(u)⁻ᵀ (geometry/moving_solid.h).
      const kernel::MovingSolid& ms = s.moving_solids[hit.index];
      const kernel::Placement x = kernel::at_time(ms, shutter_fraction(s, ray.time));
      const Vec3 n = kernel::normal_at(s.accel.prims.shapes, ms.solid, int(hit.b1), kernel::object_point(x, sp.p));
      sp.geometric_normal = sp.normal = kernel::world_normal(x, n);
      sp.texcoord = sp.p;
      sp.material = ms.solid.material;
      sp.offset = ray_offset(ray, hit.t, sp.p, 0);
      break;
    }
    case ShapeKind::Instance:
    case ShapeKind::MovingInstance: {
      const InstanceSurface is = hit.kind == ShapeKind::Instance
                                     ? instance_surface(s, sp.p, hit)
                                     : moving_instance_surface(s, shutter_fraction(s, ray.time), sp.p, hit);
      sp.geometric_normal = is.geometric_normal;
      sp.normal = is.normal;
      sp.texcoord = is.texcoord;
      sp.material = is.material;
      sp.offset = ray_offset(ray, hit.t, sp.p, is.magnitude);
      break;
    }
    case ShapeKind::None:
    default:  // (every kind is above; this tells the compiler so)
      sp.geometric_normal = sp.normal = sp.texcoord = Vec3(0);
      sp.material = 0;
      sp.offset = ray_offset(ray, hit.t, sp.p, 0);
      break;
  }
}

STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE SurfacePoint surface_at(const SceneView& s, const Ray& ray, const Hit& hit) {
  SurfacePointSlot slot;
  surface_at(s, ray, hit, slot.sp);
  return slot.sp;
}

}  // namespace strahl

namespace strahl {

// A secondary ray leaving the surface point (ray.h's spawn_ray with the point's own offset).
STRAHL_HOST_DEVICE inline Ray spawn_ray(const SurfacePoint& sp, const Vec3& direction, Real time) {
  return spawn_ray(sp.p, sp.geometric_normal, direction, time, sp.offset);
}

}  // namespace strahl
