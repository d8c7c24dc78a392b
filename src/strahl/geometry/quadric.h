#pragma once
// The general quadric Ax² + By² + Cz² + Dxy + Exz + Fyz + Gx + Hy + Iz + J = 0 (POV-Ray's ten
// coefficients, in that order), the solid being where it is < 0; optionally clipped by a box, of
// which only the surface inside is kept (POV-Ray's clipped_by: no caps, so a clipped quadric is
// an open surface). Along a ray it is a quadratic, formed from the origin moved next to a point
// of interest (the clip box's centre, else the world origin). Parts: 0.

#include "strahl/geometry/solid_crossing.h"

namespace strahl::kernel {

struct Quadric {
  Real coef[10] = {};
  bool clipped = false;
  Vec3 lo, hi;  // the clip box
};

STRAHL_HOST_DEVICE inline Real quadric_value(const Quadric& q, const Vec3& p) {
  const Real* c = q.coef;
  return p.x * (c[0] * p.x + c[3] * p.y + c[4] * p.z + c[6]) + p.y * (c[1] * p.y + c[5] * p.z + c[7]) +
         p.z * (c[2] * p.z + c[8]) + c[9];
}

STRAHL_HOST_DEVICE inline Vec3 quadric_gradient(const Quadric& q, const Vec3& p) {
  const Real* c = q.coef;
  return {2 * c[0] * p.x + c[3] * p.y + c[4] * p.z + c[6], 2 * c[1] * p.y + c[3] * p.x + c[5] * p.z + c[7],
          2 * c[2] * p.z + c[4] * p.x + c[5] * p.y + c[8]};
}

STRAHL_HOST_DEVICE inline void line_crossings(const Quadric& q, const Ray& ray, CrossingList& out) {
  Real lo = -kInfinity, hi = kInfinity;  // the line's range within the clip box
  if (q.clipped) {
    for (int a = 0; a < 3; ++a) {
      const Real d = ray.direction[a], o = ray.origin[a];
      if (d == 0) {
        if (o < q.lo[a] || o > q.hi[a]) return;
        continue;
      }
      Real t0 = (q.lo[a] - o) / d, t1 = (q.hi[a] - o) / d;
      if (t0 > t1) { const Real tmp = t0; t0 = t1; t1 = tmp; }
      lo = t0 > lo ? t0 : lo;
      hi = t1 < hi ? t1 : hi;
    }
    if (!(lo <= hi)) return;
  }
  const ShiftedRay r = shifted_ray(ray, q.clipped ? (q.lo + q.hi) * Real(0.5) : Vec3(0));
  const Real* c = q.coef;
  const Vec3& d = r.direction;
  const Real a = d.x * (c[0] * d.x + c[3] * d.y + c[4] * d.z) + d.y * (c[1] * d.y + c[5] * d.z) + d.z * c[2] * d.z;
  const Real b = dot(quadric_gradient(q, r.origin), d);
  const Real cc = quadric_value(q, r.origin);
  Real roots[2];
  const int n = quadratic_roots(a, b, cc, roots);
  for (int i = 0; i < n; ++i) {
    const Real t = r.t(roots[i]);
    if (t >= lo && t <= hi) out.add(t, 0, 2 * a * roots[i] + b < 0);
  }
  out.finish(false);
}

STRAHL_HOST_DEVICE inline Vec3 normal_at(const Quadric& q, const Vec3& p) {
  const Vec3 g = quadric_gradient(q, p);
  const Real len = length(g);
  return len > 0 ? g / len : Vec3(0, 1, 0);  // a singular point (a cone's apex): any normal
}

STRAHL_HOST_DEVICE inline bool inside(const Quadric& q, const Vec3& p) {
  if (q.clipped && !(p.x > q.lo.x && p.x < q.hi.x && p.y > q.lo.y && p.y < q.hi.y && p.z > q.lo.z && p.z < q.hi.z))
    return false;
  return quadric_value(q, p) < 0;
}

}  // namespace strahl::kernel
