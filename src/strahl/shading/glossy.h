#pragma once
// Glossy reflection and translucency (Cook, Porter, Carpenter 1984): instead of the one mirror
// (or refracted) direction, a direction drawn from a Phong-like lobe around it,
//   p(ω) = (e + 1)/(2π) · cos^e θ,   θ the angle to the ideal direction,
// with exponent e = 2/r² − 2 for roughness r ∈ (0, 1] (r → 0: the ideal direction; r = 1:
// uniform over the hemisphere around it). Averaged over a pixel's samples this blurs reflections
// and refractions.

#include <cmath>

#include "strahl/math/frame.h"
#include "strahl/math/trig.h"
#include "strahl/math/vec2.h"
#include "strahl/sampling/warp.h"

namespace strahl {

STRAHL_HOST_DEVICE inline Real glossy_exponent(Real roughness) { return 2 / (roughness * roughness) - 2; }

// A direction around the unit `axis` with density (e + 1)/(2π) cos^e θ, in world space.
STRAHL_HOST_DEVICE inline Vec3 sample_phong_lobe(const Vec3& axis, Real exponent, const Vec2& u) {
  const Real cos_theta = std::pow(u.x, 1 / (exponent + 1));
  const Real sin_theta = sqrt_clamped(1 - cos_theta * cos_theta);
  const SinCos phi = sin_cos_pi(2 * u.y);  // φ = 2π·u.y
  return normalize(Frame::around(axis).to_world({sin_theta * phi.cos, sin_theta * phi.sin, cos_theta}));
}
STRAHL_HOST_DEVICE inline Real phong_lobe_pdf(Real cos_theta, Real exponent) {
  return cos_theta > 0 ? (exponent + 1) / (2 * kPi) * std::pow(cos_theta, exponent) : 0;
}

// The ideal direction `ideal` perturbed for roughness r. The result stays on the side of the
// surface (normal n) that `ideal` is on: a sample that crosses it is mirrored at the surface.
STRAHL_HOST_DEVICE inline Vec3 glossy_direction(const Vec3& ideal, const Vec3& n, Real roughness, const Vec2& u) {
  if (roughness <= 0) return ideal;
  Vec3 d = sample_phong_lobe(ideal, glossy_exponent(roughness), u);
  const Real side = dot(ideal, n), dn = dot(d, n);
  if ((side >= 0) != (dn >= 0)) d = normalize(d - n * (2 * dn));
  return d;
}

}  // namespace strahl
