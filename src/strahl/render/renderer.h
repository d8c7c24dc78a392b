#pragma once
// The CPU backend: the image cut into tiles, tiles rendered in parallel by oneTBB. Each pixel is
// a pure function of the scene, so the image is bit-identical for any thread count or tile size.

#include <atomic>
#include <functional>

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
};

struct RenderStats {
  RayCounters rays;
  double seconds = 0;
  bool cancelled = false;  // options.cancel was set before every tile was done
};

// Called from worker threads after each finished tile with (pixels done, pixels in all);
// must be thread-safe. Not called per ray.
using ProgressCallback = std::function<void(long done, long total)>;

Image render(const RenderScene& scene, const RenderOptions& options, RenderStats* stats = nullptr,
             const ProgressCallback& progress = {});

}  // namespace strahl
