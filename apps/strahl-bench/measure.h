#pragma once
// Timing: structure builds and ray batches, each on a TBB arena of a given number of threads,
// the best of a few runs.

#include <cstdint>
#include <limits>
#include <vector>

#include "rays.h"
#include "strahl/accel/accel.h"

namespace strahl::bench {

// How often to repeat a measurement: until `min_seconds` have been spent in it or `max_runs`
// runs were made, whichever comes first; the fastest run counts.
struct Repeat {
  double min_seconds = 0.3;
  int max_runs = 5;
};

enum class Query { Nearest, Occluded };

inline constexpr std::uint32_t kMiss = std::numeric_limits<std::uint32_t>::max();

struct TraceResult {
  double seconds = 0;        // fastest run, traversal only
  std::size_t rays = 0;      // rays traced: every `stride`-th of the batch
  std::size_t stride = 1;
  std::uint64_t hits = 0;    // the checksum: rays that hit (nearest) or are occluded
  std::vector<std::uint32_t> answers;  // per traced ray: nearest primitive or kMiss; occluded 1/0
  std::vector<float> t;                 // per traced ray, nearest-hit queries: the hit's t
  double mrays() const { return seconds > 0 ? double(rays) / seconds * 1e-6 : 0; }
  double ns_per_ray() const { return rays > 0 ? seconds / double(rays) * 1e9 : 0; }
};

// Traces every `stride`-th ray of the batch with `threads` threads.
TraceResult trace(const AccelView& view, const RayBatch& batch, Query query, int threads, std::size_t stride,
                  const Repeat& repeat);

// Rays whose answer differs from `reference`'s for the same ray (reference traced every ray, or
// at least the same ones): one hits and the other does not, or they hit different primitives
// at different distances (two primitives at the same t, within 1e-5 relative, are both right).
std::size_t differing(const TraceResult& result, const TraceResult& reference);

struct BuildResult {
  Accel accel;
  double seconds = 0;  // fastest build
};

BuildResult timed_build(AccelKind kind, const PrimitiveSet& prims, int threads, const Repeat& repeat);

}  // namespace strahl::bench
