#pragma once
// Mirror reflection, Snell's law and Schlick's Fresnel approximation.

#include <cmath>

#include "strahl/math/vec3.h"

namespace strahl {

// The lecture's R = 2N(N·L) − L with L = −d pointing back along the incoming ray.
STRAHL_HOST_DEVICE inline Vec3 reflect(const Vec3& d, const Vec3& n) { return d - n * (2 * dot(d, n)); }

// Refraction of unit direction d at a surface with unit normal n facing the incoming side
// (dot(d, n) < 0), eta = n1/n2. Snell: sin θ2 = eta · sin θ1. Returns false on total internal
// reflection (eta · sin θ1 > 1), where no transmitted ray exists.
STRAHL_HOST_DEVICE inline bool refract(const Vec3& d, const Vec3& n, Real eta, Vec3& out) {
  const Real cos1 = -dot(d, n);
  const Real sin2_sq = eta * eta * (1 - cos1 * cos1);
  if (sin2_sq > 1) return false;
  const Real cos2 = std::sqrt(1 - sin2_sq);
  out = normalize(d * eta + n * (eta * cos1 - cos2));
  return true;
}

// Schlick's approximation of the Fresnel reflectance between media n1 (incoming) and n2.
// cos_i is the cosine on the incoming side; from dense to thin media the transmitted angle is used.
STRAHL_HOST_DEVICE inline Real schlick(Real cos_i, Real n1, Real n2) {
  Real r0 = (n1 - n2) / (n1 + n2);
  r0 *= r0;
  Real c = cos_i;
  if (n1 > n2) {
    const Real eta = n1 / n2;
    const Real sin2_sq = eta * eta * (1 - cos_i * cos_i);
    if (sin2_sq > 1) return 1;
    c = std::sqrt(1 - sin2_sq);
  }
  const Real x = 1 - c;
  return r0 + (1 - r0) * x * x * x * x * x;
}

}  // namespace strahl
