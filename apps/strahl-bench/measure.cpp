#include "measure.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

namespace strahl::bench {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

template <class Run>
double fastest(const Repeat& repeat, Run&& run) {
  double best = std::numeric_limits<double>::infinity(), total = 0;
  int runs = 0;
  do {
    const double t = run();
    best = std::min(best, t);
    total += t;
    ++runs;
  } while (runs < repeat.max_runs && total < repeat.min_seconds);
  return best;
}

}  // namespace

TraceResult trace(const AccelView& view, const RayBatch& batch, Query query, int threads, std::size_t stride,
                  const Repeat& repeat) {
  TraceResult r;
  r.stride = std::max<std::size_t>(1, stride);
  r.rays = (batch.size() + r.stride - 1) / r.stride;
  r.answers.assign(r.rays, 0);
  if (query == Query::Nearest) r.t.assign(r.rays, 0);
  const Ray* rays = batch.rays.data();
  const Real* t_max = batch.t_max.empty() ? nullptr : batch.t_max.data();
  std::uint32_t* answers = r.answers.data();
  float* hit_t = r.t.data();
  const std::size_t step = r.stride;
  // Small chunks when each ray is expensive (the naive loop over a large scene).
  const std::size_t grain = step > 1 ? 16 : 1024;
  tbb::task_arena arena(threads);
  r.seconds = fastest(repeat, [&] {
    const auto start = Clock::now();
    arena.execute([&] {
      if (query == Query::Nearest) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, r.rays, grain), [&](const auto& range) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const NearestHit h = nearest_hit(view, rays[i * step], 0, t_max ? t_max[i * step] : kInfinity);
            answers[i] = h.hit.t < kInfinity ? h.prim : kMiss;
            hit_t[i] = float(h.hit.t);
          }
        });
      } else {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, r.rays, grain), [&](const auto& range) {
          for (std::size_t i = range.begin(); i != range.end(); ++i)
            answers[i] = occluded(view, rays[i * step], 0, t_max ? t_max[i * step] : kInfinity) ? 1 : 0;
        });
      }
    });
    return seconds_since(start);
  });
  for (std::uint32_t a : r.answers) r.hits += (query == Query::Nearest ? a != kMiss : a != 0);
  return r;
}

std::size_t differing(const TraceResult& result, const TraceResult& reference) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < result.rays; ++i) {
    const std::size_t ray = i * result.stride;
    if (ray % reference.stride != 0 || ray / reference.stride >= reference.rays) continue;
    const std::size_t j = ray / reference.stride;
    const std::uint32_t a = result.answers[i], b = reference.answers[j];
    if (a == b) continue;
    if (result.t.empty() || reference.t.empty() || a == kMiss || b == kMiss) {
      ++n;
      continue;
    }
    const float ta = result.t[i], tb = reference.t[j];
    n += std::fabs(ta - tb) > 1e-5f * std::max(1.0f, tb);
  }
  return n;
}

BuildResult timed_build(AccelKind kind, const PrimitiveSet& prims, int threads, const Repeat& repeat) {
  BuildResult out;
  tbb::task_arena arena(threads);
  out.seconds = fastest(repeat, [&] {
    Accel accel;
    const auto start = Clock::now();
    arena.execute([&] { accel = build_accel(kind, prims); });
    const double seconds = seconds_since(start);
    out.accel = std::move(accel);  // freeing the previous run's structure is not timed
    return seconds;
  });
  return out;
}

}  // namespace strahl::bench
