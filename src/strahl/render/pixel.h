#pragma once
// One camera sample of a pixel through the pixel sampler and the integrator, and the box-filtered
// mean of a pixel's first `spp` samples: the reference the film reproduces exactly for
// pixel-local filters (render/film.h). `row` counts from the top of the image.

#include "strahl/render/integrator.h"
#include "strahl/sampling/pixel_sampler.h"

namespace strahl {

// pixel_sequence() in two steps, for a loop over many pixels (render/tile_renderer.cpp): what
// the sequences of all pixels share …
STRAHL_HOST_DEVICE inline PixelSequence shared_sequence(const SceneView& s, const PixelSampler& sampler) {
  // Time matters only to moving shapes (ray.time is read nowhere else): a static scene's samples
  // leave it at 0 without computing it, whatever the shutter interval.
  const bool uses_time = s.camera.shutter_close != s.camera.shutter_open && s.moving_count() > 0;
  return sampler.sequence(s.camera.lens_radius > 0, uses_time);
}
// … and what is pixel (x, row)'s own.
STRAHL_HOST_DEVICE inline void place_sequence(const SceneView& s, PixelSequence& p, int x, int row) {
  const int y = s.camera.ny - 1 - row;  // the lecture counts y from the bottom
  PixelSampler::place(p, x, y, std::uint64_t(y) * std::uint64_t(s.camera.nx) + std::uint64_t(x));
}

// The samples of pixel (x, row).
STRAHL_HOST_DEVICE inline PixelSequence pixel_sequence(const SceneView& s, const PixelSampler& sampler, int x, int row) {
  PixelSequence p = shared_sequence(s, sampler);
  place_sequence(s, p, x, row);
  return p;
}

// Radiance of sample `index` of a pixel; `cs` receives the camera sample it used (`observer`:
// sample_radiance's).
template <class Observer = NoTraceObserver>
STRAHL_HOST_DEVICE inline Vec3 pixel_sample(const SceneView& s, const PixelSequence& p, std::uint32_t index,
                                            CameraSample& cs, RayCounters& counters, Observer* observer = nullptr) {
  cs = p.sample(index);
  SampleStream rng{p.stream, index};
  return sample_radiance(s, cs, rng, counters, observer);
}

// Mean of samples 0 … spp−1 (in index order, as the film adds them).
STRAHL_HOST_DEVICE inline Vec3 render_pixel(const SceneView& s, int x, int row, const SamplingSettings& settings,
                                            RayCounters& counters) {
  const PixelSequence p = pixel_sequence(s, make_pixel_sampler(settings), x, row);
  const int spp = effective_spp(settings.sampler, settings.spp);
  Vec3 sum{0};
  for (int i = 0; i < spp; ++i) {
    CameraSample cs;
    sum += pixel_sample(s, p, std::uint32_t(i), cs, counters);
  }
  return sum / Real(spp);
}

// The lecture's N×N regular supersampling (N = 1: one ray through the pixel centre).
STRAHL_HOST_DEVICE inline Vec3 render_pixel(const SceneView& s, int x, int row, int supersample,
                                            RayCounters& counters) {
  SamplingSettings settings;
  settings.spp = supersample * supersample;
  return render_pixel(s, x, row, settings, counters);
}

}  // namespace strahl
