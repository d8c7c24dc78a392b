#include "strahl/render/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <vector>

#include "strahl/render/pixel.h"

namespace strahl {

Image render(const RenderScene& scene, const RenderOptions& options, RenderStats* stats,
             const ProgressCallback& progress) {
  const SceneView view = scene.view();
  const int width = view.camera.nx, height = view.camera.ny;
  const int tile = std::max(1, options.tile_size);
  const int tiles_x = (width + tile - 1) / tile, tiles_y = (height + tile - 1) / tile;
  const int tile_count = tiles_x * tiles_y;
  const long total = long(width) * height;

  Image image(width, height);
  std::vector<RayCounters> tile_counters(tile_count);
  std::atomic<long> done{0};
  std::atomic<bool> cancelled{false};
  const auto start = std::chrono::steady_clock::now();

  const auto render_tile = [&](int index) {
    if (options.cancel && options.cancel->load(std::memory_order_relaxed)) {
      cancelled.store(true, std::memory_order_relaxed);
      return;
    }
    const int x0 = (index % tiles_x) * tile, y0 = (index / tiles_x) * tile;
    const int x1 = std::min(width, x0 + tile), y1 = std::min(height, y0 + tile);
    RayCounters counters;
    for (int row = y0; row < y1; ++row) {
      for (int x = x0; x < x1; ++x) {
        const Vec3 c = render_pixel(view, x, row, scene.supersample, counters);
        image.at(x, row) = Rgb{float(c.x), float(c.y), float(c.z)};
      }
    }
    tile_counters[index] = counters;
    const long now_done = done.fetch_add(long(x1 - x0) * (y1 - y0)) + long(x1 - x0) * (y1 - y0);
    if (progress) progress(now_done, total);
  };

  const int threads = options.threads > 0 ? options.threads : tbb::task_arena::automatic;
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, tile_count, 1),
                      [&](const tbb::blocked_range<int>& r) {
                        for (int i = r.begin(); i != r.end(); ++i) render_tile(i);
                      },
                      tbb::simple_partitioner());
  });

  if (stats) {
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->cancelled = cancelled.load();
    stats->rays = {};
    for (const RayCounters& c : tile_counters) stats->rays += c;
  }
  return image;
}

}  // namespace strahl
