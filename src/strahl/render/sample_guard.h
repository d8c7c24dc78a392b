#pragma once
// The film's guard: a sample whose radiance is NaN or infinite (a division by zero deep in some
// shading formula) would poison a whole pixel and every filter footprint it touches. It becomes
// black instead and is counted, so the statistics show that something went wrong.

#include <cmath>
#include <cstdint>

#include "strahl/math/vec3.h"
#include "strahl/render/ray_counters.h"

namespace strahl {

// A finite Real that the film's float cannot hold (over 3.4e38) would turn into infinity when
// stored, so it counts as invalid too.
inline constexpr Real kFilmMax = Real(3.4028234663852886e38);  // FLT_MAX

// The one per-value test: |x| ≤ FLT_MAX is false for NaN and ±∞ as well, so it says "finite and
// storable in the film's float" at once.
STRAHL_HOST_DEVICE inline bool within_film(Real x) { return std::fabs(x) <= kFilmMax; }

STRAHL_HOST_DEVICE inline Vec3 guard_sample(const Vec3& radiance, RayCounters& counters) {
  if (within_film(radiance.x) && within_film(radiance.y) && within_film(radiance.z)) return radiance;
  ++counters.invalid_samples;
  return Vec3{0};
}

// guard_sample's test of N radiances (r[i], g[i], b[i]) side by side: bit i set where lane i passes.
template <int N>
STRAHL_HOST_DEVICE inline std::uint32_t valid_lanes(const Real* r, const Real* g, const Real* b) {
  std::uint32_t valid = 0;
  for (int i = 0; i < N; ++i)
    valid |= std::uint32_t(int(within_film(r[i])) & int(within_film(g[i])) & int(within_film(b[i])))
             << i;
  return valid;
}

}  // namespace strahl
