#pragma once
// Radiance of one pixel: N×N regular supersampling with a box filter (N = 1: the lecture's one
// ray through the pixel centre). `row` counts from the top of the image.

#include "strahl/render/integrator.h"

namespace strahl {

STRAHL_HOST_DEVICE inline Vec3 render_pixel(const SceneView& s, int x, int row, int supersample,
                                            RayCounters& counters) {
  const int n = supersample;
  const Real inv_n = Real(1) / n;
  const int y = s.camera.ny - 1 - row;  // the lecture counts y from the bottom
  Vec3 sum{0};
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      CameraSample cs;
      cs.film_x = x + (i + Real(0.5)) * inv_n;
      cs.film_y = y + (j + Real(0.5)) * inv_n;
      SampleStream rng{0, std::uint64_t(y) * std::uint64_t(s.camera.nx) + std::uint64_t(x), std::uint32_t(j * n + i)};
      if (s.camera.lens_radius > 0) cs.lens = {random_real(0, rng.pixel, rng.sample, kDimLens), random_real(0, rng.pixel, rng.sample, kDimLens + 1)};
      if (s.moving_sphere_count + s.moving_triangle_count > 0) cs.time = random_real(0, rng.pixel, rng.sample, kDimTime);
      sum += sample_radiance(s, cs, rng, counters);
    }
  }
  return sum * (inv_n * inv_n);
}

}  // namespace strahl
