#pragma once
// The rays every structure traces, made once per scene before any timing: primary rays through
// the pixel centres, and from each primary hit one incoherent ray (cosine-distributed about the
// normal) and one shadow ray (to the point light).

#include <cstdint>
#include <vector>

#include "scenes.h"
#include "strahl/accel/accel.h"

namespace strahl::bench {

struct RayBatch {
  std::vector<Ray> rays;
  std::vector<Real> t_max;  // per ray; empty: ∞ for all
  Real t_max_of(std::size_t i) const { return t_max.empty() ? kInfinity : t_max[i]; }
  std::size_t size() const { return rays.size(); }
};

inline constexpr std::uint32_t kNoRay = ~std::uint32_t(0);

struct BenchRays {
  int width = 0, height = 0;
  RayBatch primary;     // width × height, row by row from the top; nearest hit
  RayBatch incoherent;  // one per primary hit; nearest hit
  RayBatch shadow;      // one per primary hit, t_max = distance to the light; any hit (occluded)
  std::vector<std::uint32_t> secondary_of_pixel;  // per pixel: its incoherent and shadow ray, or kNoRay (a miss)
};

// Finds the primary hits with `reference` (strahl's BVH) to place the secondary rays. Each
// pixel's random numbers come from (seed, pixel index) alone.
BenchRays make_rays(const BenchScene& scene, const AccelView& reference, std::uint64_t seed = 1);

}  // namespace strahl::bench
