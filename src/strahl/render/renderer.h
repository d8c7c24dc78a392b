#pragma once
// render(): one render job (render/render_job.h) on the CPU back end (render/cpu_backend.h), for
// callers that want the image and nothing else — the lecture's API, the tests, Python.
// The image is bit-identical for any thread count or tile size.

#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "strahl/image/image.h"
#include "strahl/render/render_job.h"
#include "strahl/render/render_scene.h"

namespace strahl {

struct RenderOptions {
  int threads = 0;     // 0: all cores
  int tile_size = 32;  // pixels along a tile's side
  // When set and it becomes true (a signal handler, a time limit), rendering stops between two
  // samples; RenderStats::cancelled says so.
  const std::atomic<bool>* cancel = nullptr;
  // Seconds after which rendering stops (0: none): the image keeps every sample taken so far,
  // each pixel weighted by its own count.
  double time_limit = 0;
  // Called with the image so far every `checkpoint_interval` seconds (0: never), from a worker
  // thread, one call at a time.
  double checkpoint_interval = 0;
  std::function<void(const Image&)> checkpoint{};
};

Image render(const RenderScene& scene, const RenderOptions& options, RenderStats* stats = nullptr,
             const ProgressCallback& progress = {});

}  // namespace strahl
