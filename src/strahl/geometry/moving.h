#pragma once
// Moving shapes for motion blur: each stores its placement at shutter open and at shutter close
// and moves linearly in between (a linear velocity gives exactly that; two keyframed transforms
// are interpolated vertex by vertex). A ray meets the shape where it is at the ray's time,
// given as u ∈ [0, 1] over the shutter. The box over both placements bounds every position in
// between (points move on segments), so a BVH over these swept boxes is exact.

#include <cmath>
#include <cstdint>

#include "strahl/geometry/sphere.h"
#include "strahl/geometry/triangle.h"
#include "strahl/math/bounds.h"

namespace strahl::kernel {

STRAHL_HOST_DEVICE inline Vec3 lerp(const Vec3& a, const Vec3& b, Real u) { return a + (b - a) * u; }

// Centre and radius move linearly from shutter open to close (a keyframed uniform scale
// changes the radius).
struct MovingSphere {
  Vec3 center0, center1;  // at shutter open, at shutter close
  Real radius0 = 1, radius1 = 1;
  std::uint32_t material = 0;
};

STRAHL_HOST_DEVICE inline Sphere at_time(const MovingSphere& s, Real u) {
  return Sphere{lerp(s.center0, s.center1, u), s.radius0 + (s.radius1 - s.radius0) * u, s.material};
}

// Each coordinate of the box at time u is linear in u, so the boxes at the two ends hold it.
inline Bounds swept_bounds(const MovingSphere& s) {
  Bounds b;
  b.extend(s.center0 - Vec3(s.radius0)); b.extend(s.center0 + Vec3(s.radius0));
  b.extend(s.center1 - Vec3(s.radius1)); b.extend(s.center1 + Vec3(s.radius1));
  return b;
}

struct MovingTriangle {
  Vec3 p0[3];  // vertices at shutter open
  Vec3 p1[3];  // at shutter close
  std::uint32_t material = 0;
  std::int32_t normals = -1;  // vertex normals: [normals] at open, [normals + 1] at close; −1 flat
  std::uint32_t object = 0;
};

struct TriangleAtTime {
  Vec3 a, b, c;
};

STRAHL_HOST_DEVICE inline TriangleAtTime at_time(const MovingTriangle& t, Real u) {
  return {lerp(t.p0[0], t.p1[0], u), lerp(t.p0[1], t.p1[1], u), lerp(t.p0[2], t.p1[2], u)};
}

inline Bounds swept_bounds(const MovingTriangle& t) {
  Bounds b;
  for (int i = 0; i < 3; ++i) { b.extend(t.p0[i]); b.extend(t.p1[i]); }
  return b;
}

// The watertight test (triangle.h) on the triangle where it is at time u: t and barycentrics
// (b1, b2) of b and c. Neighbours interpolate their shared vertices alike, so they stay watertight.
struct MovingTriangleHit {
  Real t = kInfinity;
  Real b1 = 0, b2 = 0;
};

STRAHL_HOST_DEVICE inline MovingTriangleHit intersect(const TriangleAtTime& tri, const Ray& ray, Real t_min, Real t_max) {
  const TriangleHit h = intersect(tri.a, tri.b, tri.c, ray, ray_shear(ray.direction), t_min, t_max);
  return {h.t, h.b1, h.b2};
}

STRAHL_HOST_DEVICE inline Vec3 geometric_normal(const TriangleAtTime& tri) {
  return normalize(cross(tri.b - tri.a, tri.c - tri.a));
}

}  // namespace strahl::kernel
