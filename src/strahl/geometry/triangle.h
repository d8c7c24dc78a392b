#pragma once
// Ray–triangle intersection by barycentric coordinates (Möller–Trumbore): the lecture's
// "intersect the triangle's plane, then test whether the point lies inside" in one solve of
// o + t·d = v0 + b1·e1 + b2·e2.

#include <cmath>
#include <cstdint>

#include "strahl/math/ray.h"

namespace strahl::kernel {

struct Triangle {
  Vec3 v0, e1, e2;             // v1 = v0 + e1, v2 = v0 + e2
  std::uint32_t material = 0;
  std::int32_t normals = -1;  // index into the vertex-normal array, −1 for flat shading
  std::uint32_t object = 0;   // which scene object (mesh) it belongs to
};

// Per-vertex shading normals of a triangle, interpolated with the barycentric coordinates.
struct VertexNormals {
  Vec3 n0, n1, n2;
};

struct TriangleHit {
  Real t = kInfinity;
  Real b1 = 0, b2 = 0;
};

STRAHL_HOST_DEVICE inline TriangleHit intersect(const Triangle& tri, const Ray& ray, Real t_min, Real t_max) {
  TriangleHit hit;
  const Vec3 pvec = cross(ray.direction, tri.e2);
  const Real det = dot(tri.e1, pvec);
  if (det == 0) return hit;  // ray parallel to the triangle's plane (or a degenerate triangle)
  const Real inv_det = Real(1) / det;
  const Vec3 tvec = ray.origin - tri.v0;
  const Real b1 = dot(tvec, pvec) * inv_det;
  if (b1 < 0 || b1 > 1) return hit;
  const Vec3 qvec = cross(tvec, tri.e1);
  const Real b2 = dot(ray.direction, qvec) * inv_det;
  if (b2 < 0 || b1 + b2 > 1) return hit;
  const Real t = dot(tri.e2, qvec) * inv_det;
  if (t > t_min && t < t_max) hit = {t, b1, b2};
  return hit;
}

// Unit geometric normal, oriented by the winding v0 → v1 → v2 (counter-clockwise seen from the front).
STRAHL_HOST_DEVICE inline Vec3 geometric_normal(const Triangle& tri) { return normalize(cross(tri.e1, tri.e2)); }

}  // namespace strahl::kernel
