#pragma once
// An orthonormal basis {u, v, w}, right-handed (u × v = w), as the lecture builds the camera.

#include "strahl/math/vec3.h"

namespace strahl {

struct Frame {
  Vec3 u, v, w;

  // The camera basis: w points from the look-at point back to the eye (the camera looks along -w),
  // u = up × w to the right, v = w × u up.
  static Frame look_at(const Vec3& eye, const Vec3& target, const Vec3& up) {
    Frame f;
    f.w = normalize(eye - target);
    f.u = normalize(cross(up, f.w));
    f.v = cross(f.w, f.u);
    return f;
  }

  // Some right-handed basis with w = n (unit): for local sample directions around a normal or
  // axis (Duff et al. 2017, branchless).
  STRAHL_HOST_DEVICE static Frame around(const Vec3& n) {
    const Real sign = n.z >= 0 ? Real(1) : Real(-1);
    const Real a = Real(-1) / (sign + n.z);
    const Real b = n.x * n.y * a;
    Frame f;
    f.u = Vec3(1 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    f.v = Vec3(b, sign + n.y * n.y * a, -n.y);
    f.w = n;
    return f;
  }

  // Local coordinates (x, y, z) along (u, v, w) to world space.
  STRAHL_HOST_DEVICE Vec3 to_world(const Vec3& local) const { return u * local.x + v * local.y + w * local.z; }
};

}  // namespace strahl
