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
};

}  // namespace strahl
