#pragma once
// Rays traced, by kind, kept per tile and summed at the end (no shared counters in the hot path).

#include <cstdint>

namespace strahl {

struct RayCounters {
  std::uint64_t camera = 0, shadow = 0, reflection = 0, refraction = 0;
  std::uint64_t invalid_samples = 0;  // samples whose radiance was NaN or infinite (set to black)
  std::uint64_t cut = 0;  // reflected or refracted rays not traced: their camera sample's ray budget was spent

  constexpr std::uint64_t total() const { return camera + shadow + reflection + refraction; }
  constexpr RayCounters& operator+=(const RayCounters& o) {
    camera += o.camera; shadow += o.shadow; reflection += o.reflection; refraction += o.refraction;
    invalid_samples += o.invalid_samples;
    cut += o.cut;
    return *this;
  }
};

}  // namespace strahl
