#pragma once
// Moving shapes for motion blur: each stores its placement at shutter open and at shutter close
// and moves linearly in between (a linear velocity gives exactly that; two keyframed transforms
// are interpolated vertex by vertex). A ray meets the shape where it is at the ray's time,
// given as u ∈ [0, 1] over the shutter. The box over both placements bounds every position in
// between (points move on segments), so a BVH over these swept boxes is exact.

#include <cmath>
#include <cstdint>
#include <initializer_list>

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

// The box holding the sphere at every time of [u0, u1] (u0 ≤ u1): at_time's centre and radius are
// monotone in u even as rounded (a + (b − a)·u), so they lie between their values at u0 and u1.
inline Bounds swept_bounds(const MovingSphere& s, Real u0, Real u1) {
  const Sphere a = at_time(s, u0), b = at_time(s, u1);
  const Vec3 r(a.radius > b.radius ? a.radius : b.radius);
  return Bounds{min(a.center, b.center) - r, max(a.center, b.center) + r};
}
inline Bounds swept_bounds(const MovingSphere& s) { return swept_bounds(s, 0, 1); }

struct MovingTriangle {
  Vec3 p0[3];  // vertices at shutter open
  Vec3 p1[3];  // at shutter close
  std::uint32_t material = 0;
  std::int32_t normals = -1;  // vertex normals: [normals] at open, [normals + 1] at close; −1 flat
  std::uint32_t object = 0;
  std::int32_t texcoords = -1;  // vertex texture coordinates (the same at open and close), −1 none
};

struct TriangleAtTime {
  Vec3 a, b, c;
};

STRAHL_HOST_DEVICE inline TriangleAtTime at_time(const MovingTriangle& t, Real u) {
  return {lerp(t.p0[0], t.p1[0], u), lerp(t.p0[1], t.p1[1], u), lerp(t.p0[2], t.p1[2], u)};
}

// The box holding the triangle at every time of [u0, u1] (u0 ≤ u1): each vertex's at_time
// coordinates are monotone in u even as rounded, so the vertices at u0 and u1 bound them.
inline Bounds swept_bounds(const MovingTriangle& t, Real u0, Real u1) {
  const TriangleAtTime a = at_time(t, u0), b = at_time(t, u1);
  Bounds box;
  for (const Vec3& p : {a.a, a.b, a.c, b.a, b.b, b.c}) box.extend(p);
  return box;
}
inline Bounds swept_bounds(const MovingTriangle& t) { return swept_bounds(t, 0, 1); }

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
