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

STRAHL_HOST_DEVICE inline Vec3 guard_sample(const Vec3& radiance, RayCounters& counters) {
  if (is_finite(radiance) && std::fabs(radiance.x) <= kFilmMax && std::fabs(radiance.y) <= kFilmMax &&
      std::fabs(radiance.z) <= kFilmMax)
    return radiance;
  ++counters.invalid_samples;
  return Vec3{0};
}

// guard_sample's test of N radiances (r[i], g[i], b[i]) side by side: bit i set where lane i
// passes (|x| ≤ FLT_MAX is false for NaN and ±∞ as well, so the finiteness test is implied).
template <int N>
STRAHL_HOST_DEVICE inline std::uint32_t valid_lanes(const Real* r, const Real* g, const Real* b) {
  std::uint32_t valid = 0;
  for (int i = 0; i < N; ++i)
    valid |= std::uint32_t(int(std::fabs(r[i]) <= kFilmMax) & int(std::fabs(g[i]) <= kFilmMax) &
                           int(std::fabs(b[i]) <= kFilmMax))
             << i;
  return valid;
}

}  // namespace strahl
