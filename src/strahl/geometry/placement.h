#pragma once
// A solid placed by an affine transform (scene keys scale, rotate, translate): the shape is
// intersected in its own (object) space with the ray brought there by the inverse transform —
// the ray's t is the same in both spaces, since the map is affine — and its normals are brought
// back by the inverse transpose. A sphere scaled unevenly is an ellipsoid this way.

#include <cstdint>

#include "strahl/math/ray.h"

namespace strahl::kernel {

// world → object: p_object = to_object · (p_world − translate).
struct Placement {
  Vec3 row[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  // the inverse of the linear part, by rows
  Vec3 translate{0};
};

STRAHL_HOST_DEVICE inline Vec3 object_vector(const Placement& x, const Vec3& v) {
  return {dot(x.row[0], v), dot(x.row[1], v), dot(x.row[2], v)};
}
STRAHL_HOST_DEVICE inline Vec3 object_point(const Placement& x, const Vec3& p) {
  return object_vector(x, p - x.translate);
}
STRAHL_HOST_DEVICE inline Ray object_ray(const Placement& x, const Ray& ray) {
  return Ray{object_point(x, ray.origin), object_vector(x, ray.direction), ray.time};
}
// An object-space normal in world space: (linear part)^−T · n = to_objectᵀ · n, normalised.
STRAHL_HOST_DEVICE inline Vec3 world_normal(const Placement& x, const Vec3& n) {
  return normalize(x.row[0] * n.x + x.row[1] * n.y + x.row[2] * n.z);
}

}  // namespace strahl::kernel
