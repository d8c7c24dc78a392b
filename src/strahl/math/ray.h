#pragma once
// The lecture's ray p(t) = e + t·d. Directions are kept normalised, so t is a distance.

#include "strahl/math/vec3.h"

namespace strahl {

struct Ray {
  Vec3 origin;
  Vec3 direction;
  Real time = 0;  // when in the shutter interval the ray travels (motion blur)

  STRAHL_HOST_DEVICE constexpr Vec3 at(Real t) const { return origin + direction * t; }
};

// A secondary ray leaving surface point `p` with geometric normal `n`: its origin is pushed off
// the surface by `offset` to the side the ray travels into, so that it cannot hit the surface it
// starts on (no shadow acne). `offset` bounds the error of p (SurfacePoint::offset: relative to
// the magnitudes p was computed from, so the same at any scene scale); by default kRayEpsilon·|p|.
// `time` is the parent ray's: all rays of one camera sample see the scene at one instant.
STRAHL_HOST_DEVICE inline Ray spawn_ray(const Vec3& p, const Vec3& n, const Vec3& direction, Real time, Real offset) {
  const Real side = dot(direction, n) >= 0 ? Real(1) : Real(-1);
  return Ray{p + n * (side * offset), direction, time};
}
STRAHL_HOST_DEVICE inline Ray spawn_ray(const Vec3& p, const Vec3& n, const Vec3& direction, Real time = 0) {
  return spawn_ray(p, n, direction, time, kRayEpsilon * max_abs_component(p));
}

}  // namespace strahl
