#pragma once
// What every analytic solid answers along a ray: its surface crossings over the whole line,
// sorted by t, each with the part of the surface it is on (a box face, a cylinder's cap…) and
// whether the line enters the solid there. The nearest hit, the shadow ray's crossings and (for
// closed solids) the entry/exit intervals that CSG combines are all read from this one list.

#include <cstdint>

#include "strahl/math/ray.h"

namespace strahl::kernel {

struct SolidCrossing {
  Real t = kInfinity;
  std::uint32_t part = 0;  // which piece of the surface (for the normal); kind-specific (CSG: geometry/csg.h)
  bool entering = false;  // from outside the solid to inside along the ray
};

// At most four crossings: a torus, a capped cone with rounding at both rims, a clipped quadric.
inline constexpr int kMaxLineCrossings = 4;

struct CrossingList {
  SolidCrossing c[kMaxLineCrossings];
  int n = 0;

  STRAHL_HOST_DEVICE void add(Real t, int part, bool entering) {
    if (n < kMaxLineCrossings && t == t) c[n++] = {t, std::uint32_t(part), entering};
  }
  // Sorts by t (insertion sort: at most four) and, for a closed solid, drops a crossing that
  // repeats the previous one's direction (a ray through a rim met by the side and by the cap at
  // one point), so that entries and exits alternate.
  STRAHL_HOST_DEVICE void finish(bool closed) {
    for (int i = 1; i < n; ++i)
      for (int j = i; j > 0 && c[j].t < c[j - 1].t; --j) {
        const SolidCrossing tmp = c[j];
        c[j] = c[j - 1];
        c[j - 1] = tmp;
      }
    if (!closed) return;
    int m = 0;
    for (int i = 0; i < n; ++i)
      if (m == 0 || c[i].entering != c[m - 1].entering) c[m++] = c[i];
    n = m;
  }
};

// The real roots of a u² + b u + c = 0 (stable form: q = −(b + sign(b)·√D)/2, roots q/a and
// c/q), in any order; a = 0 gives the linear root. Returns how many (0..2).
STRAHL_HOST_DEVICE inline int quadratic_roots(Real a, Real b, Real c, Real roots[2]) {
  if (a == 0) {
    if (b == 0) return 0;
    roots[0] = -c / b;
    return 1;
  }
  const Real disc = b * b - 4 * a * c;
  if (disc < 0) return 0;
  const Real q = Real(-0.5) * (b + std::copysign(std::sqrt(disc), b));
  if (q == 0) {  // b = c = 0: a double root at 0
    roots[0] = 0;
    return 1;
  }
  roots[0] = q / a;
  roots[1] = c / q;
  return 2;
}

// The ray as the analytic solids solve it: a unit direction and the origin moved along the line
// to the point nearest `ref` (a point of the solid), so that the coefficients are formed from
// values of the solid's own size even when the ray starts 1e5 away. t = (shift + u)·inv_speed
// for a distance u from that origin.
struct ShiftedRay {
  Vec3 origin;     // the point of the line nearest ref
  Vec3 direction;  // unit
  Real shift = 0;  // distance from the ray's origin to `origin`
  Real inv_speed = 1;
  STRAHL_HOST_DEVICE Real t(Real u) const { return (shift + u) * inv_speed; }
};

STRAHL_HOST_DEVICE inline ShiftedRay shifted_ray(const Ray& ray, const Vec3& ref) {
  ShiftedRay r;
  const Real speed = length(ray.direction);
  r.inv_speed = Real(1) / speed;
  r.direction = ray.direction * r.inv_speed;
  r.shift = dot(ref - ray.origin, r.direction);
  r.origin = ray.origin + r.direction * r.shift;
  return r;
}

}  // namespace strahl::kernel
