#include "packets.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "strahl/accel/packet.h"

namespace strahl::bench {

namespace {

using Clock = std::chrono::steady_clock;

template <int N>
void trace_range(const AccelView& view, const PacketBatch& pb, Query query, std::size_t begin, std::size_t end,
                 std::uint32_t* answers, kernel::TriangleHit* hits) {
  const Real zero[N] = {};
  for (std::size_t p = begin; p != end; ++p) {
    const Ray* rays = pb.rays.data() + p * N;
    const Real* t_max = pb.t_max.data() + p * N;
    const std::uint32_t* index = pb.ray.data() + p * N;
    const std::uint32_t active = pb.active[p];
    if (query == Query::Nearest) {
      NearestHit out[N];
      nearest_hit_packet<N>(view, active, rays, zero, t_max, out);
      for (int i = 0; i < N; ++i) {
        if (((active >> i) & 1u) == 0) continue;
        answers[index[i]] = out[i].hit.t < kInfinity ? out[i].prim : kMiss;
        hits[index[i]] = out[i].hit;
      }
    } else {
      const std::uint32_t occ = occluded_packet<N>(view, active, rays, zero, t_max);
      for (int i = 0; i < N; ++i)
        if ((active >> i) & 1u) answers[index[i]] = (occ >> i) & 1u;
    }
  }
}

}  // namespace

PacketBatch tile_packets(const BenchRays& rays, int size, bool secondary) {
  PacketBatch pb;
  pb.size = size;
  pb.tile_width = 4;
  pb.tile_height = size / 4;
  const RayBatch& batch = secondary ? rays.shadow : rays.primary;
  for (int ty = 0; ty < rays.height; ty += pb.tile_height) {
    for (int tx = 0; tx < rays.width; tx += pb.tile_width) {
      std::uint32_t active = 0;
      std::uint32_t index[16];
      for (int i = 0; i < size; ++i) {
        const int x = tx + i % pb.tile_width, y = ty + i / pb.tile_width;
        index[i] = kNoRay;
        if (x >= rays.width || y >= rays.height) continue;
        const std::size_t pixel = std::size_t(y) * std::size_t(rays.width) + std::size_t(x);
        index[i] = secondary ? rays.secondary_of_pixel[pixel] : std::uint32_t(pixel);
        if (index[i] != kNoRay) active |= 1u << i;
      }
      if (active == 0) continue;
      const std::uint32_t any = index[__builtin_ctz(active)];
      for (int i = 0; i < size; ++i) {
        const std::uint32_t r = index[i] != kNoRay ? index[i] : any;
        pb.rays.push_back(batch.rays[r]);
        pb.t_max.push_back(batch.t_max_of(r));
        pb.ray.push_back(index[i]);
      }
      pb.active.push_back(active);
      pb.ray_count += std::size_t(__builtin_popcount(active));
    }
  }
  return pb;
}

PacketTrace trace_packets(const AccelView& view, const PacketBatch& pb, std::size_t batch_size, Query query,
                          int threads, const Repeat& repeat) {
  PacketTrace r;
  r.rays = pb.ray_count;
  r.answers.assign(batch_size, query == Query::Nearest ? kMiss : 0);
  if (query == Query::Nearest) r.hits.assign(batch_size, kernel::TriangleHit{});
  std::uint32_t* answers = r.answers.data();
  kernel::TriangleHit* hits = r.hits.data();
  tbb::task_arena arena(threads);
  double best = std::numeric_limits<double>::infinity(), total = 0;
  int runs = 0;
  do {
    const auto start = Clock::now();
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pb.packets(), 64), [&](const auto& range) {
        if (pb.size == 8)
          trace_range<8>(view, pb, query, range.begin(), range.end(), answers, hits);
        else
          trace_range<16>(view, pb, query, range.begin(), range.end(), answers, hits);
      });
    });
    const double t = std::chrono::duration<double>(Clock::now() - start).count();
    best = std::min(best, t);
    total += t;
    ++runs;
  } while (runs < repeat.max_runs && total < repeat.min_seconds);
  r.seconds = best;
  return r;
}

PacketTrace trace_single(const AccelView& view, const RayBatch& batch, Query query, int threads) {
  PacketTrace r;
  r.rays = batch.size();
  r.answers.assign(batch.size(), 0);
  if (query == Query::Nearest) r.hits.assign(batch.size(), kernel::TriangleHit{});
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, batch.size(), 1024), [&](const auto& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        if (query == Query::Nearest) {
          const NearestHit h = nearest_hit(view, batch.rays[i], 0, batch.t_max_of(i));
          r.answers[i] = h.hit.t < kInfinity ? h.prim : kMiss;
          r.hits[i] = h.hit;
        } else {
          r.answers[i] = occluded(view, batch.rays[i], 0, batch.t_max_of(i)) ? 1 : 0;
        }
      }
    });
  });
  return r;
}

PacketDiff compare(const PacketTrace& packets, const PacketTrace& single, bool exact) {
  PacketDiff d;
  for (std::size_t i = 0; i < packets.answers.size() && i < single.answers.size(); ++i) {
    const std::uint32_t a = packets.answers[i], b = single.answers[i];
    if (packets.hits.empty() || single.hits.empty()) {  // occluded
      d.differ += a != b;
      continue;
    }
    const kernel::TriangleHit &ha = packets.hits[i], &hb = single.hits[i];
    if (exact) {
      if (a == b && std::memcmp(&ha, &hb, sizeof ha) == 0) continue;
      if (a != b && a != kMiss && b != kMiss && ha.t == hb.t)
        ++d.ties;
      else
        ++d.differ;
      continue;
    }
    if (a == b) continue;
    if (a == kMiss || b == kMiss) {
      ++d.differ;
      continue;
    }
    d.differ += std::fabs(ha.t - hb.t) > 1e-5 * std::max(1.0, hb.t);
  }
  return d;
}

}  // namespace strahl::bench
