#pragma once
// A torus: centre, unit axis, major radius R (centre to the tube's centre circle) and minor
// radius r < R (the tube's). In its own frame (z along the axis) the surface is
//   (x² + y² + z² + R² − r²)² − 4R²(x² + y²) = 0,
// a quartic in the ray's distance u. Robust in double: the origin is first moved along the ray
// to the point nearest the centre (ShiftedRay), so the coefficients are formed from values of the
// torus's own size at any distance from the world origin; the roots are then bracketed within the
// bounding sphere's chord and found by Newton steps inside their brackets (polynomial.h), which
// polishes each to the last bits. Parts: 0 (one surface).

#include "strahl/geometry/polynomial.h"
#include "strahl/geometry/solid_crossing.h"

namespace strahl::kernel {

struct Torus {
  Vec3 center;
  Vec3 axis;  // unit
  Real major = 1, minor = Real(0.25);
};

STRAHL_HOST_DEVICE inline void line_crossings(const Torus& s, const Ray& ray, CrossingList& out) {
  const ShiftedRay r = shifted_ray(ray, s.center);
  const Vec3 o = r.origin - s.center;  // ⟂ to the direction
  const Real bound = s.major + s.minor;
  const Real rho2 = dot(o, o);
  if (!(rho2 <= bound * bound)) return;  // misses the bounding sphere (NaN too)
  // The chord of the bounding sphere, a little wider: every root lies within it.
  const Real half = std::sqrt(bound * bound - rho2) * (1 + Real(1e-9)) + bound * Real(1e-12);
  const Real oz = dot(o, s.axis), dz = dot(r.direction, s.axis);
  const Real R2 = s.major * s.major;
  // |p|² = u² + 2b·u + |o|² with b = o·d = 0 after the shift, up to rounding: kept for exactness.
  const Real b = dot(o, r.direction);
  const Real k = rho2 + R2 - s.minor * s.minor;
  const Real oxy = rho2 - oz * oz, dxy = 1 - dz * dz, odxy = b - oz * dz;
  const Real c[5] = {k * k - 4 * R2 * oxy, 4 * b * k - 8 * R2 * odxy, 4 * b * b + 2 * k - 4 * R2 * dxy, 4 * b, 1};
  Real roots[4];
  const int n = polynomial_roots<4>(c, -half, half, roots);
  // Entering where the quartic falls through zero: the sign of its derivative.
  for (int i = 0; i < n; ++i) {
    const Real u = roots[i];
    const Real slope = ((4 * u + 3 * c[3]) * u + 2 * c[2]) * u + c[1];
    out.add(r.t(u), 0, slope < 0);
  }
  out.finish(true);
}

// normalize(p − R·(p projected onto the torus's plane, normalised)), from the centre.
STRAHL_HOST_DEVICE inline Vec3 normal_at(const Torus& s, const Vec3& p) {
  const Vec3 q = p - s.center;
  const Vec3 in_plane = q - s.axis * dot(q, s.axis);
  const Real len = length(in_plane);
  if (!(len > 0)) return s.axis;
  return normalize(q - in_plane * (s.major / len));
}

STRAHL_HOST_DEVICE inline bool inside(const Torus& s, const Vec3& p) {
  const Vec3 q = p - s.center;
  const Real z = dot(q, s.axis);
  const Real radial = length(q - s.axis * z) - s.major;
  return radial * radial + z * z < s.minor * s.minor;
}

}  // namespace strahl::kernel
