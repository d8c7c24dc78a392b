#pragma once
// The lecture's camera: eye e, orthonormal basis {u, v, w}, image plane bounds l, r, b, t at
// distance d, an n_x × n_y pixel grid with a half-pixel border. The ray through raster position
// (x, y) (pixel centres at x + 0.5; y counted from the bottom row) has direction
//   s_u·u + s_v·v − d·w,  s_u = l + (r − l)·x/n_x,  s_v = b + (t − b)·y/n_y.

//
// Thin lens (depth of field): with lens radius a > 0 the ray starts at a point of the lens disk
// (cs.lens by the concentric map) and passes through the point where the pinhole ray meets the
// focus plane, at distance focus_distance along the view axis −w. Points on that plane are
// sharp; a point at depth z blurs into a disk of radius a·d·|1/f − 1/z| on the image plane.
// Shutter: the ray's time is shutter_open + cs.time · (shutter_close − shutter_open).

#include <cmath>

#include "strahl/camera/camera_sample.h"
#include "strahl/math/frame.h"
#include "strahl/math/ray.h"
#include "strahl/sampling/warp.h"

namespace strahl {

struct Camera {
  Vec3 eye;
  Frame basis;
  Real l = -1, r = 1, b = -1, t = 1, d = 1;
  int nx = 1, ny = 1;
  Real lens_radius = 0;     // 0: the pinhole camera
  Real focus_distance = 1;  // of the plane in focus, along −w
  Real shutter_open = 0, shutter_close = 0;

  // (x, y) in raster units: x ∈ [0, n_x) left to right, y ∈ [0, n_y) bottom to top.
  STRAHL_HOST_DEVICE Ray generate_ray(Real x, Real y) const {
    const Real su = l + (r - l) * x / nx;
    const Real sv = b + (t - b) * y / ny;
    return Ray{eye, normalize(basis.u * su + basis.v * sv - basis.w * d)};
  }

  // The directions of generate_ray(x[i], y[i]) for N raster positions at once, into d?[i]: the
  // same arithmetic lane by lane, as a loop over plain arrays that the compiler turns into SIMD.
  template <int N>
  STRAHL_HOST_DEVICE void directions(const Real* x, const Real* y, Real* dx, Real* dy, Real* dz) const {
    for (int i = 0; i < N; ++i) {
      const Real su = l + (r - l) * x[i] / nx;
      const Real sv = b + (t - b) * y[i] / ny;
      const Real px = basis.u.x * su + basis.v.x * sv - basis.w.x * d;
      const Real py = basis.u.y * su + basis.v.y * sv - basis.w.y * d;
      const Real pz = basis.u.z * su + basis.v.z * sv - basis.w.z * d;
      const Real inv = Real(1) / std::sqrt(px * px + py * py + pz * pz);  // normalize()
      dx[i] = px * inv, dy[i] = py * inv, dz[i] = pz * inv;
    }
  }

  // The ray for one camera sample: film position, lens position (thin lens) and shutter time.
  STRAHL_HOST_DEVICE Ray generate_ray(const CameraSample& cs) const {
    Ray ray = generate_ray(cs.film_x, cs.film_y);
    ray.time = shutter_open + cs.time * (shutter_close - shutter_open);
    if (lens_radius > 0) through_lens(ray, cs.lens);
    return ray;
  }

  // The pinhole ray turned into the thin-lens ray from lens sample `lens` (see above). Kept out
  // of line: the pinhole camera's path stays small.
  STRAHL_HOST_DEVICE STRAHL_NOINLINE void through_lens(Ray& ray, const Vec2& lens) const { lens_ray(ray, lens); }

  // through_lens() inlined, for loops over lanes of camera rays (render/packet_radiance.h) that
  // the compiler vectorises.
  STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void lens_ray(Ray& ray, const Vec2& lens) const {
    const Vec3 focus = ray.at(focus_distance / -dot(ray.direction, basis.w));
    const Vec2 on_lens = square_to_disk(lens);
    ray.origin = eye + (basis.u * on_lens.x + basis.v * on_lens.y) * lens_radius;
    ray.direction = normalize(focus - ray.origin);
  }
};

}  // namespace strahl
