#pragma once
// An axis-aligned box (POV-Ray's box: two opposite corners): the slab test, over the whole line.
// Parts are faces: 2·axis for the lower face on that axis, 2·axis + 1 for the upper one.

#include "strahl/geometry/solid_crossing.h"

namespace strahl::kernel {

struct Box {
  Vec3 lo, hi;
};

STRAHL_HOST_DEVICE inline void line_crossings(const Box& b, const Ray& ray, CrossingList& out) {
  Real t0 = -kInfinity, t1 = kInfinity;
  int face0 = 0, face1 = 1;
  for (int a = 0; a < 3; ++a) {
    const Real d = ray.direction[a], o = ray.origin[a];
    if (d == 0) {
      if (o < b.lo[a] || o > b.hi[a]) return;  // parallel to the slab and outside it
      continue;
    }
    const Real inv = Real(1) / d;
    Real near = (b.lo[a] - o) * inv, far = (b.hi[a] - o) * inv;
    int near_face = 2 * a, far_face = 2 * a + 1;
    if (near > far) {
      const Real tmp = near; near = far; far = tmp;
      near_face = 2 * a + 1;
      far_face = 2 * a;
    }
    if (near > t0) { t0 = near; face0 = near_face; }
    if (far < t1) { t1 = far; face1 = far_face; }
  }
  if (!(t0 <= t1)) return;
  out.add(t0, face0, true);
  out.add(t1, face1, false);
}

STRAHL_HOST_DEVICE inline Vec3 normal_at(const Box&, int face) {
  const Real s = (face & 1) ? Real(1) : Real(-1);
  const int a = face >> 1;
  return a == 0 ? Vec3(s, 0, 0) : a == 1 ? Vec3(0, s, 0) : Vec3(0, 0, s);
}

STRAHL_HOST_DEVICE inline bool inside(const Box& b, const Vec3& p) {
  return p.x > b.lo.x && p.x < b.hi.x && p.y > b.lo.y && p.y < b.hi.y && p.z > b.lo.z && p.z < b.hi.z;
}

}  // namespace strahl::kernel
