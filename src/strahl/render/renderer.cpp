#include "strahl/render/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <vector>

#include "strahl/render/adaptive.h"
#include "strahl/render/film.h"
#include "strahl/render/pixel.h"

namespace strahl {

namespace {
using Clock = std::chrono::steady_clock;
}

Image render(const RenderScene& scene, const RenderOptions& options, RenderStats* stats,
             const ProgressCallback& progress) {
  const SceneView view = scene.view();
  const SamplingSettings& sampling = scene.sampling;
  const PixelSampler sampler = make_pixel_sampler(sampling);
  const int width = view.camera.nx, height = view.camera.ny;
  const int tile = std::max(1, options.tile_size);
  const int tiles_x = (width + tile - 1) / tile, tiles_y = (height + tile - 1) / tile;
  const int tile_count = tiles_x * tiles_y;
  const std::size_t pixel_count = std::size_t(width) * std::size_t(height);

  const auto max_spp = std::uint32_t(effective_spp(sampling.sampler, sampling.spp));
  const bool adaptive = sampling.sampler == SamplerKind::Adaptive;
  const bool timed = options.time_limit > 0;
  const bool progressive = adaptive || timed || options.checkpoint_interval > 0;

  Film film(width, height, sampling.filter, adaptive);
  std::vector<std::uint32_t> counts(pixel_count, 0);
  // First pass: all samples, or 1 (progressive), or the adaptive minimum.
  const std::uint32_t first =
      adaptive ? std::min(max_spp, std::uint32_t(std::max(1, sampling.adaptive_min))) : progressive ? 1 : max_spp;
  std::vector<std::uint32_t> add(pixel_count, first);
  std::uint64_t pass_samples = std::uint64_t(first) * pixel_count;

  std::vector<RayCounters> tile_counters(tile_count);
  std::atomic<std::uint64_t> done{0};
  std::atomic<bool> cancelled{false}, out_of_time{false};
  const auto start = Clock::now();
  const auto deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                                    timed ? options.time_limit : 0.0));
  std::mutex checkpoint_mutex;
  const auto checkpoint_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(std::max(0.0, options.checkpoint_interval)));
  auto next_checkpoint = start + checkpoint_period;  // guarded by checkpoint_mutex
  // Samples the render may still take in all (adaptive: an upper bound that shrinks pass by pass).
  std::uint64_t planned = std::uint64_t(max_spp) * pixel_count;

  const auto stop_requested = [&] {
    if (options.cancel && options.cancel->load(std::memory_order_relaxed)) {
      cancelled.store(true, std::memory_order_relaxed);
      return true;
    }
    if (timed && Clock::now() >= deadline) {
      out_of_time.store(true, std::memory_order_relaxed);
      return true;
    }
    return false;
  };

  const auto report = [&](std::uint64_t now_done) {
    if (!progress) return;
    if (timed) {
      const double f_samples = double(now_done) / double(std::max<std::uint64_t>(planned, 1));
      const double f_time = std::chrono::duration<double>(Clock::now() - start).count() / options.time_limit;
      progress(long(std::min(1.0, std::max(f_samples, f_time)) * 1e6), 1000000);
    } else {
      progress(long(now_done), long(planned));
    }
  };

  const auto render_tile = [&](int index) {
    if (stop_requested()) return;
    const int x0 = (index % tiles_x) * tile, y0 = (index / tiles_x) * tile;
    const int x1 = std::min(width, x0 + tile), y1 = std::min(height, y0 + tile);
    Film::Tile ft = film.begin_tile(x0, y0, x1, y1);
    RayCounters counters;
    std::uint64_t tile_samples = 0;
    bool stopped = false;
    for (int row = y0; row < y1 && !stopped; ++row) {
      for (int x = x0; x < x1; ++x) {
        if (progressive && stop_requested()) {
          stopped = true;
          break;
        }
        const std::size_t p = std::size_t(row) * std::size_t(width) + std::size_t(x);
        const std::uint32_t begin = counts[p], end = begin + add[p];
        if (begin == end) continue;
        const PixelSequence sequence = pixel_sequence(view, sampler, x, row);
        for (std::uint32_t k = begin; k < end; ++k) {
          CameraSample cs;
          const Vec3 L = pixel_sample(view, sequence, k, cs, counters);
          film.add_sample(ft, x, row, cs, L);
        }
        counts[p] = end;
        tile_samples += end - begin;
      }
    }
    film.end_tile(ft);
    tile_counters[index] += counters;
    report(done.fetch_add(tile_samples) + tile_samples);
    if (options.checkpoint && checkpoint_period.count() > 0 && Clock::now() >= next_checkpoint) {
      std::unique_lock lock(checkpoint_mutex, std::try_to_lock);
      if (lock.owns_lock() && Clock::now() >= next_checkpoint) {
        options.checkpoint(film.resolve());
        next_checkpoint = Clock::now() + checkpoint_period;
      }
    }
  };

  const int threads = options.threads > 0 ? options.threads : tbb::task_arena::automatic;
  tbb::task_arena arena(threads);
  int passes = 0;
  while (pass_samples > 0) {
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, tile_count, 1),
                        [&](const tbb::blocked_range<int>& r) {
                          for (int i = r.begin(); i != r.end(); ++i) render_tile(i);
                        },
                        tbb::simple_partitioner());
    });
    ++passes;
    if (cancelled.load() || out_of_time.load()) break;
    if (adaptive) {
      pass_samples = plan_adaptive_pass(film, counts, max_spp, sampling.adaptive_threshold, add);
      std::uint64_t bound = done.load();
      for (std::size_t p = 0; p < pixel_count; ++p)
        if (add[p] > 0) bound += max_spp - counts[p];
      planned = bound;
    } else {
      // Double every pixel's count (all pixels have the same).
      const std::uint32_t c = counts.empty() ? max_spp : counts[0];
      const std::uint32_t next = std::min(c, max_spp - c);
      std::fill(add.begin(), add.end(), next);
      pass_samples = std::uint64_t(next) * pixel_count;
    }
  }

  if (stats) {
    stats->seconds = std::chrono::duration<double>(Clock::now() - start).count();
    stats->cancelled = cancelled.load();
    stats->time_limited = out_of_time.load();
    stats->rays = {};
    for (const RayCounters& c : tile_counters) stats->rays += c;
    stats->samples = done.load();
    stats->passes = passes;
    stats->pixel_samples = std::move(counts);
  }
  return film.resolve();
}

}  // namespace strahl
