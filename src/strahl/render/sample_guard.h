#pragma once
// The film's guard: a sample whose radiance is NaN or infinite (a division by zero deep in some
// shading formula) would poison a whole pixel and every filter footprint it touches. It becomes
// black instead and is counted, so the statistics show that something went wrong.

#include <cmath>

#include "strahl/math/vec3.h"
#include "strahl/render/ray_counters.h"

namespace strahl {

// A finite Real that the film's float cannot hold (over 3.4e38) would turn into infinity when
// stored, so it counts as invalid too.
STRAHL_HOST_DEVICE inline Vec3 guard_sample(const Vec3& radiance, RayCounters& counters) {
  constexpr Real kFilmMax = Real(3.4028234663852886e38);  // FLT_MAX
  if (is_finite(radiance) && std::fabs(radiance.x) <= kFilmMax && std::fabs(radiance.y) <= kFilmMax &&
      std::fabs(radiance.z) <= kFilmMax)
    return radiance;
  ++counters.invalid_samples;
  return Vec3{0};
}

}  // namespace strahl
