#pragma once
// Warps from the unit square to the shapes the Monte Carlo estimators sample, each with its
// density (with respect to area for the disk, solid angle for directions). Directions are in a
// local frame with z as the axis; math/frame.h turns them into world space. Angles go through
// sin_cos_pi (math/trig.h): the same bits on the CPU and the GPU.

#include <cmath>

#include "strahl/math/trig.h"
#include "strahl/math/vec2.h"
#include "strahl/math/vec3.h"

namespace strahl {

// √max(0, x): the root of a quantity that rounding may push just below zero (1 − z², 1 − cos²).
// A comparison rather than std::fmax, which GCC compiles to a call into libm (for its NaN
// rules; a NaN x gives 0 either way).
STRAHL_HOST_DEVICE inline Real sqrt_clamped(Real x) { return std::sqrt(x > 0 ? x : Real(0)); }

// Shirley–Chiu concentric map: the square onto the unit disk, uniform, low distortion. Written
// with selections rather than branches, so that a loop over lanes of samples vectorises.
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE Vec2 square_to_disk(const Vec2& u) {
  const Real a = 2 * u.x - 1, b = 2 * u.y - 1;
  const bool by_a = a * a > b * b;
  const Real r = by_a ? a : b;
  const SinCos phi = sin_cos_pi(by_a ? Real(0.25) * (b / a) : Real(0.5) - Real(0.25) * (a / b));
  const bool centre = a == 0 && b == 0;  // where the angle is 0/0
  return {centre ? Real(0) : r * phi.cos, centre ? Real(0) : r * phi.sin};
}
STRAHL_HOST_DEVICE inline Real disk_pdf() { return 1 / kPi; }

// Uniform on the hemisphere z ≥ 0.
STRAHL_HOST_DEVICE inline Vec3 square_to_uniform_hemisphere(const Vec2& u) {
  const Real z = u.x;
  const Real r = sqrt_clamped(1 - z * z);
  const SinCos phi = sin_cos_pi(2 * u.y);  // φ = 2π·u.y
  return {r * phi.cos, r * phi.sin, z};
}
STRAHL_HOST_DEVICE inline Real uniform_hemisphere_pdf() { return 1 / (2 * kPi); }

// Cosine-weighted on the hemisphere z ≥ 0 (Malley: the disk lifted onto the hemisphere).
STRAHL_HOST_DEVICE inline Vec3 square_to_cosine_hemisphere(const Vec2& u) {
  const Vec2 d = square_to_disk(u);
  return {d.x, d.y, sqrt_clamped(1 - d.x * d.x - d.y * d.y)};
}
STRAHL_HOST_DEVICE inline Real cosine_hemisphere_pdf(Real cos_theta) { return cos_theta > 0 ? cos_theta / kPi : 0; }

// Uniform on the whole unit sphere.
STRAHL_HOST_DEVICE inline Vec3 square_to_uniform_sphere(const Vec2& u) {
  const Real z = 1 - 2 * u.x;
  const Real r = sqrt_clamped(1 - z * z);
  const SinCos phi = sin_cos_pi(2 * u.y);  // φ = 2π·u.y
  return {r * phi.cos, r * phi.sin, z};
}
STRAHL_HOST_DEVICE inline Real uniform_sphere_pdf() { return 1 / (4 * kPi); }

// Uniform in the cone of directions within angle θ_max of +z (cos_max = cos θ_max).
STRAHL_HOST_DEVICE inline Vec3 square_to_uniform_cone(const Vec2& u, Real cos_max) {
  const Real z = 1 - u.x * (1 - cos_max);
  const Real r = sqrt_clamped(1 - z * z);
  const SinCos phi = sin_cos_pi(2 * u.y);  // φ = 2π·u.y
  return {r * phi.cos, r * phi.sin, z};
}
STRAHL_HOST_DEVICE inline Real uniform_cone_pdf(Real cos_max) { return 1 / (2 * kPi * (1 - cos_max)); }

}  // namespace strahl
