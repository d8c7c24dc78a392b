#pragma once
// The CPU backend: the image cut into tiles, tiles rendered in parallel by oneTBB, samples
// splatted into the film (render/film.h). Each pixel is a pure function of the scene and the
// sampling settings, so the image is bit-identical for any thread count or tile size.
//
// Progressive rendering (adaptive sampling, a time limit or checkpoints): passes over the whole
// image, each doubling the samples per pixel (1, 1, 2, 4, … up to spp; adaptive: the minimum,
// then doubling where render/adaptive.h says so). Without those, one pass takes all spp.

#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "strahl/image/image.h"
#include "strahl/render/ray_counters.h"
#include "strahl/render/render_scene.h"

namespace strahl {

struct RenderOptions {
  int threads = 0;     // 0: all cores
  int tile_size = 32;  // pixels along a tile's side
  // When set and it becomes true (a signal handler, a time limit), tiles not yet started are
  // skipped; their pixels stay black and RenderStats::cancelled says so.
  const std::atomic<bool>* cancel = nullptr;
  // Seconds after which rendering stops (0: none): pixels stop between samples, mid-pass; the
  // image keeps every sample taken so far, each pixel weighted by its own count.
  double time_limit = 0;
  // Called with the image so far every `checkpoint_interval` seconds (0: never), from a worker
  // thread, one call at a time.
  double checkpoint_interval = 0;
  std::function<void(const Image&)> checkpoint{};
};

struct RenderStats {
  RayCounters rays;
  double seconds = 0;
  bool cancelled = false;  // options.cancel was set before every tile was done
  bool time_limited = false;  // stopped by options.time_limit
  std::uint64_t samples = 0;  // camera samples taken
  int passes = 0;
  std::vector<std::uint32_t> pixel_samples{};  // samples per pixel, row-major from the top
};

// Called from worker threads after each finished tile with (pixels done, pixels in all);
// must be thread-safe. Not called per ray. Units are samples; with a time limit the fraction of
// the limit used when that is larger.
using ProgressCallback = std::function<void(long done, long total)>;

Image render(const RenderScene& scene, const RenderOptions& options, RenderStats* stats = nullptr,
             const ProgressCallback& progress = {});

}  // namespace strahl
