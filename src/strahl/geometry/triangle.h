#pragma once
// Ray–triangle intersection, watertight (Woop, Benthin, Wald: "Watertight Ray/Triangle
// Intersection", JCGT 2013). The lecture's "intersect the triangle's plane, then test whether the
// point lies inside", done in a frame where the ray is the z axis: the vertices are translated to
// the ray origin and sheared so the ray points along +z, and the three 2-D edge functions U, V, W
// say on which side of each edge the ray passes. A shared edge gives the two triangles edge
// functions of exactly opposite sign (the same products of the same vertex values, subtracted the
// other way round), so a ray through the edge or a vertex hits at least one of them: no ray slips
// between the triangles of a closed mesh. This needs the compiler not to fuse a·b − c·d into an
// FMA (which rounds the two products differently): the build uses -ffp-contract=off.
//
// Vertices are stored, not edges: v0 + (v1 − v0) need not give back v1 in floating point, and
// the edge functions of neighbouring triangles agree only when both see the same vertex values.

#include <cmath>
#include <cstdint>

#include "strahl/math/ray.h"

namespace strahl::kernel {

struct Triangle {
  Vec3 v0, v1, v2;
  std::uint32_t material = 0;
  std::int32_t normals = -1;  // index into the vertex-normal array, −1 for flat shading
  std::uint32_t object = 0;   // which scene object (mesh) it belongs to
  std::int32_t texcoords = -1;  // index into the vertex texture-coordinate array, −1 for none

  STRAHL_HOST_DEVICE Vec3 edge1() const { return v1 - v0; }
  STRAHL_HOST_DEVICE Vec3 edge2() const { return v2 - v0; }
};

// Per-vertex shading normals of a triangle, interpolated with the barycentric coordinates.
struct VertexNormals {
  Vec3 n0, n1, n2;
};

// Per-vertex texture coordinates (u, v) of a triangle (a mesh's OBJ `vt`, PLY u/v), interpolated
// with the barycentric coordinates as the normals are.
struct VertexTexcoords {
  Real u0, v0, u1, v1, u2, v2;
};

// The texture coordinate (u, v, 0) at barycentric weights b1, b2 (of vertices 1 and 2).
STRAHL_HOST_DEVICE inline Vec3 texcoord_at(const VertexTexcoords& t, Real b1, Real b2) {
  const Real b0 = 1 - b1 - b2;
  return Vec3(t.u0 * b0 + t.u1 * b1 + t.u2 * b2, t.v0 * b0 + t.v1 * b1 + t.v2 * b2, 0);
}

struct TriangleHit {
  Real t = kInfinity;
  Real b1 = 0, b2 = 0;  // barycentric weights of v1 and v2 (v0 has 1 − b1 − b2)
};

// What the watertight test needs of a ray, computed once per ray: the axis the direction is
// largest along (kz) and the two others (kx, ky, ordered so the frame keeps its winding), and
// the shear that maps the direction to (0, 0, 1).
struct RayShear {
  int kx = 0, ky = 1, kz = 2;
  Real sx = 0, sy = 0, sz = 1;
};

// The axis the ray is sheared along: that of the direction's largest |component|.
STRAHL_HOST_DEVICE inline int shear_axis(const Vec3& d) {
  const Real ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
  return ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
}

STRAHL_HOST_DEVICE inline RayShear ray_shear(const Vec3& d) {
  RayShear s;
  s.kz = shear_axis(d);
  s.kx = s.kz == 2 ? 0 : s.kz + 1;
  s.ky = s.kx == 2 ? 0 : s.kx + 1;
  if (d[s.kz] < 0) { const int tmp = s.kx; s.kx = s.ky; s.ky = tmp; }
  s.sx = d[s.kx] / d[s.kz];
  s.sy = d[s.ky] / d[s.kz];
  s.sz = Real(1) / d[s.kz];
  return s;
}

// The triangle in the ray's sheared frame (the ray along +z from the origin): the vertices
// relative to the ray's origin and the three 2D edge functions u, v, w, one per edge. Shared by
// intersect() and plane_hit(), so both compute exactly the same numbers.
struct ShearedTriangle {
  Vec3 a, b, c;
  Real u, v, w;
};

STRAHL_HOST_DEVICE inline ShearedTriangle shear_triangle(const Vec3& v0, const Vec3& v1, const Vec3& v2,
                                                         const Ray& ray, const RayShear& s) {
  ShearedTriangle t;
  t.a = v0 - ray.origin;
  t.b = v1 - ray.origin;
  t.c = v2 - ray.origin;
  const Real ax = t.a[s.kx] - s.sx * t.a[s.kz], ay = t.a[s.ky] - s.sy * t.a[s.kz];
  const Real bx = t.b[s.kx] - s.sx * t.b[s.kz], by = t.b[s.ky] - s.sy * t.b[s.kz];
  const Real cx = t.c[s.kx] - s.sx * t.c[s.kz], cy = t.c[s.ky] - s.sy * t.c[s.kz];
  t.u = cx * by - cy * bx;
  t.v = ax * cy - ay * cx;
  t.w = bx * ay - by * ax;
  return t;
}

// The distance along the ray to the triangle's plane, given det = u + v + w ≠ 0.
STRAHL_HOST_DEVICE inline Real sheared_distance(const ShearedTriangle& t, const RayShear& s, Real inv_det) {
  const Real az = s.sz * t.a[s.kz], bz = s.sz * t.b[s.kz], cz = s.sz * t.c[s.kz];
  return (t.u * az + t.v * bz + t.w * cz) * inv_det;
}

// The nearest hit in (t_min, t_max), with the ray's shear computed beforehand (ray_shear): hits on
// an edge or a vertex count (for every triangle sharing it), both sides of the triangle are hit.
STRAHL_HOST_DEVICE inline TriangleHit intersect(const Vec3& v0, const Vec3& v1, const Vec3& v2, const Ray& ray,
                                                const RayShear& s, Real t_min, Real t_max) {
  TriangleHit hit;
  const ShearedTriangle st = shear_triangle(v0, v1, v2, ray, s);
  if ((st.u < 0 || st.v < 0 || st.w < 0) && (st.u > 0 || st.v > 0 || st.w > 0)) return hit;
  const Real det = st.u + st.v + st.w;
  if (det == 0) return hit;  // the ray lies in the triangle's plane (or the triangle is degenerate)
  const Real inv_det = Real(1) / det;
  const Real t = sheared_distance(st, s, inv_det);
  if (t > t_min && t < t_max) hit = {t, st.v * inv_det, st.w * inv_det};
  return hit;
}

// The same arithmetic without the inside and range checks: where the ray meets the triangle's
// plane and the barycentrics there (a little negative when rounding put the point a hair outside),
// for a hit found by other means (Embree, in float) to get the numbers intersect() gives. t is
// kInfinity when the ray is parallel to the plane.
STRAHL_HOST_DEVICE inline TriangleHit plane_hit(const Triangle& tri, const Ray& ray, const RayShear& s) {
  TriangleHit hit;
  const ShearedTriangle st = shear_triangle(tri.v0, tri.v1, tri.v2, ray, s);
  const Real det = st.u + st.v + st.w;
  if (det == 0) return hit;
  const Real inv_det = Real(1) / det;
  return {sheared_distance(st, s, inv_det), st.v * inv_det, st.w * inv_det};
}

STRAHL_HOST_DEVICE inline TriangleHit intersect(const Triangle& tri, const Ray& ray, const RayShear& s, Real t_min,
                                                Real t_max) {
  return intersect(tri.v0, tri.v1, tri.v2, ray, s, t_min, t_max);
}

STRAHL_HOST_DEVICE inline TriangleHit intersect(const Triangle& tri, const Ray& ray, Real t_min, Real t_max) {
  return intersect(tri, ray, ray_shear(ray.direction), t_min, t_max);
}

// Unit geometric normal, oriented by the winding v0 → v1 → v2 (counter-clockwise seen from the front).
STRAHL_HOST_DEVICE inline Vec3 geometric_normal(const Triangle& tri) {
  return normalize(cross(tri.edge1(), tri.edge2()));
}

}  // namespace strahl::kernel
