#pragma once
// The film's guard: a sample whose radiance is NaN or infinite (a division by zero deep in some
// shading formula) would poison a whole pixel and every filter footprint it touches. It becomes
// black instead and is counted, so the statistics show that something went wrong.

#include "strahl/math/vec3.h"
#include "strahl/render/ray_counters.h"

namespace strahl {

STRAHL_HOST_DEVICE inline Vec3 guard_sample(const Vec3& radiance, RayCounters& counters) {
  if (is_finite(radiance)) return radiance;
  ++counters.invalid_samples;
  return Vec3{0};
}

}  // namespace strahl
