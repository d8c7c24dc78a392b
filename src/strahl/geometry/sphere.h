#pragma once
// Ray–sphere intersection, numerically robust form (Haines et al., Ray Tracing Gems ch. 7, as in
// Embree): the lecture's quadratic A t² + B t + C = 0 with A = 1 for unit directions, the
// discriminant taken from the distance of the centre to the ray instead of B² − 4AC (which
// cancels catastrophically for small spheres far away), and the two roots from the stable
// pair q, C/q instead of (−B ± √D)/2A.

#include <cmath>
#include <cstdint>

#include "strahl/geometry/solid_crossing.h"

namespace strahl::kernel {

struct Sphere {
  Vec3 center;
  Real radius = 1;
  std::uint32_t material = 0;
};

// Nearest root of the ray with the sphere in the open interval (t_min, t_max), or kInfinity.
// Rays starting inside the sphere hit it from within (the far root).
// Forced inline: it is the whole loop body of the one-leaf sphere queries (accel.h).
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE Real intersect(const Sphere& s, const Ray& ray, Real t_min, Real t_max) {
  const Vec3 f = ray.origin - s.center;
  const Real b = -dot(f, ray.direction);          // t of the point on the ray nearest the centre
  const Vec3 l = f + ray.direction * b;           // centre → that point
  const Real r2 = s.radius * s.radius;
  const Real discriminant = r2 - dot(l, l);       // (half-chord length)²
  if (discriminant < 0) return kInfinity;
  const Real c = dot(f, f) - r2;
  const Real q = b + std::copysign(std::sqrt(discriminant), b);
  Real t0 = q != 0 ? c / q : 0;
  Real t1 = q;
  if (t0 > t1) { const Real tmp = t0; t0 = t1; t1 = tmp; }
  // Find the nearest root in the acceptable range.
  if (t0 > t_min && t0 < t_max) return t0;
  if (t1 > t_min && t1 < t_max) return t1;
  return kInfinity;
}

// How many times the segment (t_min, t_max) of the ray crosses the sphere's surface: 0, 1 or 2.
STRAHL_HOST_DEVICE inline int crossings(const Sphere& s, const Ray& ray, Real t_min, Real t_max) {
  const Vec3 f = ray.origin - s.center;
  const Real b = -dot(f, ray.direction);
  const Vec3 l = f + ray.direction * b;
  const Real r2 = s.radius * s.radius;
  const Real discriminant = r2 - dot(l, l);
  if (discriminant < 0) return 0;
  const Real q = b + std::copysign(std::sqrt(discriminant), b);
  const Real t0 = q != 0 ? (dot(f, f) - r2) / q : 0, t1 = q;
  return int(t0 > t_min && t0 < t_max) + int(t1 > t_min && t1 < t_max);
}

// Outward unit normal at a surface point: (p − c)/R, as in the lecture.
STRAHL_HOST_DEVICE inline Vec3 normal_at(const Sphere& s, const Vec3& p) { return (p - s.center) / s.radius; }

// Both crossings with the whole line, for CSG (the sphere as an operand): the chord from the
// point of the line nearest the centre (ShiftedRay), exact at any distance from the origin.
STRAHL_HOST_DEVICE inline void line_crossings(const Sphere& s, const Ray& ray, CrossingList& out) {
  const ShiftedRay r = shifted_ray(ray, s.center);
  const Vec3 o = r.origin - s.center;
  const Real disc = s.radius * s.radius - dot(o, o);
  if (!(disc >= 0)) return;
  const Real half = std::sqrt(disc);
  out.add(r.t(-half), 0, true);
  out.add(r.t(half), 0, false);
}

STRAHL_HOST_DEVICE inline bool inside(const Sphere& s, const Vec3& p) {
  return length_squared(p - s.center) < s.radius * s.radius;
}

}  // namespace strahl::kernel
