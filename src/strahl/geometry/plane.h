#pragma once
// The plane N·p = d (the lecture's implicit f(p) = N·p − d, its Plane(normal, d, colour)).
// Unbounded: it stays outside every acceleration structure.

#include <cmath>
#include <cstdint>

#include "strahl/math/ray.h"

namespace strahl::kernel {

struct Plane {
  Vec3 normal;  // unit length
  Real distance = 0;
  Vec3 tangent, bitangent;  // an orthonormal frame in the plane, for 2D textures
  std::uint32_t material = 0;
};

// Root of N·(o + t·dir) = d in (t_min, t_max), or kInfinity; rays parallel to the plane miss.
STRAHL_HOST_DEVICE inline Real intersect(const Plane& p, const Ray& ray, Real t_min, Real t_max) {
  const Real denom = dot(p.normal, ray.direction);
  if (denom == 0) return kInfinity;
  const Real t = (p.distance - dot(p.normal, ray.origin)) / denom;
  return (t > t_min && t < t_max) ? t : kInfinity;
}

}  // namespace strahl::kernel
