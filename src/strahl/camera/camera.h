#pragma once
// The lecture's camera: eye e, orthonormal basis {u, v, w}, image plane bounds l, r, b, t at
// distance d, an n_x × n_y pixel grid with a half-pixel border. The ray through raster position
// (x, y) (pixel centres at x + 0.5; y counted from the bottom row) has direction
//   s_u·u + s_v·v − d·w,  s_u = l + (r − l)·x/n_x,  s_v = b + (t − b)·y/n_y.

#include "strahl/camera/camera_sample.h"
#include "strahl/math/frame.h"
#include "strahl/math/ray.h"

namespace strahl {

struct Camera {
  Vec3 eye;
  Frame basis;
  Real l = -1, r = 1, b = -1, t = 1, d = 1;
  int nx = 1, ny = 1;

  // (x, y) in raster units: x ∈ [0, n_x) left to right, y ∈ [0, n_y) bottom to top.
  STRAHL_HOST_DEVICE Ray generate_ray(Real x, Real y) const {
    const Real su = l + (r - l) * x / nx;
    const Real sv = b + (t - b) * y / ny;
    return Ray{eye, normalize(basis.u * su + basis.v * sv - basis.w * d)};
  }

  // The ray for one camera sample: the pinhole camera uses only the film position. (A thin
  // lens would use cs.lens, a shutter cs.time: they extend this function, not its callers.)
  STRAHL_HOST_DEVICE Ray generate_ray(const CameraSample& cs) const { return generate_ray(cs.film_x, cs.film_y); }
};

}  // namespace strahl
