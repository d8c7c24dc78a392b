#pragma once
// Counter-based random numbers: every value is a pure function of (seed, pixel, sample index,
// dimension), so an image does not depend on thread count, tile order or backend (DESIGN.md,
// "Determinism"). No state is carried from one sample to the next; a SampleStream only counts
// the dimensions one camera sample has used.
//
// Dimension layout of one camera sample (pixel samplers may replace the first five by their own
// stratified or low-discrepancy values):
//   0, 1  position in the pixel      2, 3  position on the lens      4  time in the shutter
//   5 …   the integrator (light samples, glossy directions, …), in the order it asks for them

#include <cstdint>

#include "strahl/math/vec2.h"

namespace strahl {

inline constexpr std::uint32_t kDimPixel = 0, kDimLens = 2, kDimTime = 4, kDimIntegrator = 5;

// SplitMix64's finaliser: a bijection on 64 bits with full avalanche.
STRAHL_HOST_DEVICE constexpr std::uint64_t mix64(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return x;
}

// 64 random bits for (seed, pixel, sample, dimension).
// The part of random_bits that depends only on (seed, pixel): computed once per pixel, it leaves
// one mix64 per random number. In two steps for a loop over pixels: the seed's part (mix_seed),
// once, then each pixel's (pixel_key_of).
STRAHL_HOST_DEVICE constexpr std::uint64_t mix_seed(std::uint64_t seed) { return mix64(seed + 0x9e3779b97f4a7c15ULL); }
STRAHL_HOST_DEVICE constexpr std::uint64_t pixel_key_of(std::uint64_t seed_mix, std::uint64_t pixel) {
  return mix64(seed_mix ^ pixel);
}
STRAHL_HOST_DEVICE constexpr std::uint64_t pixel_key(std::uint64_t seed, std::uint64_t pixel) {
  return pixel_key_of(mix_seed(seed), pixel);
}

STRAHL_HOST_DEVICE constexpr std::uint64_t keyed_bits(std::uint64_t key, std::uint32_t sample, std::uint32_t dimension) {
  return mix64(key ^ ((std::uint64_t(sample) << 32) | dimension));
}

STRAHL_HOST_DEVICE constexpr std::uint64_t random_bits(std::uint64_t seed, std::uint64_t pixel, std::uint32_t sample,
                                                       std::uint32_t dimension) {
  return keyed_bits(pixel_key(seed, pixel), sample, dimension);
}

// The top 53 bits as a double in [0, 1) (never 1).
STRAHL_HOST_DEVICE constexpr Real to_unit(std::uint64_t bits) {
  return Real(bits >> 11) * Real(1.0 / 9007199254740992.0);
}

STRAHL_HOST_DEVICE constexpr Real random_real(std::uint64_t seed, std::uint64_t pixel, std::uint32_t sample,
                                              std::uint32_t dimension) {
  return to_unit(random_bits(seed, pixel, sample, dimension));
}

// The random numbers of one camera sample, dimension after dimension.
struct SampleStream {
  std::uint64_t key = 0;  // pixel_key(seed, pixel), pixel = y · width + x
  std::uint32_t sample = 0;
  std::uint32_t dimension = kDimIntegrator;

  STRAHL_HOST_DEVICE Real next() { return to_unit(keyed_bits(key, sample, dimension++)); }
  STRAHL_HOST_DEVICE Vec2 next2() {
    const Real a = next();
    return {a, next()};
  }
};

}  // namespace strahl
