#pragma once
// Pixel samplers: the camera sample number `index` of pixel (x, y) — film position, lens position
// and time — as a pure function of (seed, pixel, index) (DESIGN.md, "Determinism").
//
//   grid        n×n sub-pixel centres (n = round(√spp)); lens and time stratified (jittered)
//   stratified  the n×n strata, each jittered; lens and time stratified and padded by permutation
//   random      independent uniform values
//   sobol       Owen-scrambled Sobol (0,2)-sequence per dimension pair, index shuffled per pixel
//               and pair (Burley 2020); good for any count and for prefixes of powers of two
//   adaptive    the sobol points, with the count per pixel chosen by render/adaptive.h
//
// Grid and stratified visit their n² strata in an order permuted per pixel, so that the first
// samples of a progressive render are spread over the pixel; a pixel's sample k ≥ n² starts a new
// round over the strata with new jitter.

#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>

#include "strahl/camera/camera_sample.h"
#include "strahl/sampling/filter.h"
#include "strahl/sampling/permute.h"
#include "strahl/sampling/rng.h"
#include "strahl/sampling/sobol.h"

namespace strahl {

enum class SamplerKind : std::uint8_t { Grid, Stratified, Random, Sobol, Adaptive };

struct SamplingSettings {
  SamplerKind sampler = SamplerKind::Grid;
  int spp = 1;                     // samples per pixel; adaptive: the maximum
  std::uint64_t seed = 0;
  Filter filter;                   // box of radius 0.5: each sample counts for its own pixel only
  int adaptive_min = 16;           // adaptive: samples every pixel gets in the first pass
  Real adaptive_threshold = 0.02;  // adaptive: relative standard error a pixel must reach
};

inline constexpr int kMaxSpp = 1 << 20;

// Grid and stratified use a square number of samples: n = round(√spp), at least 1.
inline int strata_side(int spp) { return spp <= 1 ? 1 : int(std::lround(std::sqrt(double(spp)))); }

// The sample count a sampler really takes for `spp` (squares for grid and stratified).
inline int effective_spp(SamplerKind kind, int spp) {
  if (kind == SamplerKind::Grid || kind == SamplerKind::Stratified) {
    const int n = strata_side(spp);
    return n * n;
  }
  return spp < 1 ? 1 : spp;
}

inline std::optional<SamplerKind> sampler_from_name(std::string_view name) {
  if (name == "grid" || name == "regular") return SamplerKind::Grid;
  if (name == "stratified" || name == "jittered") return SamplerKind::Stratified;
  if (name == "random" || name == "uniform") return SamplerKind::Random;
  if (name == "sobol") return SamplerKind::Sobol;
  if (name == "adaptive") return SamplerKind::Adaptive;
  return std::nullopt;
}
inline const char* sampler_name(SamplerKind kind) {
  switch (kind) {
    case SamplerKind::Grid: return "grid";
    case SamplerKind::Stratified: return "stratified";
    case SamplerKind::Random: return "random";
    case SamplerKind::Sobol: return "sobol";
    case SamplerKind::Adaptive: return "adaptive";
  }
  return "?";
}
inline constexpr const char* kSamplerNames = "grid, stratified, random, sobol, adaptive";

inline std::optional<FilterKind> filter_from_name(std::string_view name) {
  if (name == "box") return FilterKind::Box;
  if (name == "tent" || name == "triangle") return FilterKind::Tent;
  if (name == "gaussian") return FilterKind::Gaussian;
  if (name == "mitchell" || name == "mitchell-netravali") return FilterKind::Mitchell;
  return std::nullopt;
}
inline const char* filter_name(FilterKind kind) {
  switch (kind) {
    case FilterKind::Box: return "box";
    case FilterKind::Tent: return "tent";
    case FilterKind::Gaussian: return "gaussian";
    case FilterKind::Mitchell: return "mitchell";
  }
  return "?";
}
inline constexpr const char* kFilterNames = "box, tent, gaussian, mitchell";

// Kernel side: what one pixel sample needs, plain data.
struct PixelSampler {
  SamplerKind kind = SamplerKind::Grid;
  std::uint32_t side = 1;  // grid/stratified: n
  std::uint64_t seed = 0;

  // A 32-bit hash per (pixel, purpose, round), independent of the per-sample random numbers
  // (those use sample indices, these the index 0xffffffff which no sample reaches).
  STRAHL_HOST_DEVICE std::uint32_t hash(std::uint64_t pixel, std::uint32_t purpose) const {
    return std::uint32_t(random_bits(seed, pixel, 0xffffffffu, purpose) >> 32);
  }

  // Stratum `k` of `count` visited at position k in round `round`, with the value's jitter.
  STRAHL_HOST_DEVICE Real stratum_1d(std::uint64_t pixel, std::uint32_t k, std::uint32_t count, std::uint32_t purpose,
                                     Real jitter) const {
    return (Real(permutation_element(k, count, hash(pixel, purpose))) + jitter) / Real(count);
  }
  STRAHL_HOST_DEVICE Vec2 stratum_2d(std::uint64_t pixel, std::uint32_t k, std::uint32_t purpose, Vec2 jitter) const {
    const std::uint32_t s = permutation_element(k, side * side, hash(pixel, purpose));
    return {(Real(s % side) + jitter.x) / Real(side), (Real(s / side) + jitter.y) / Real(side)};
  }
  STRAHL_HOST_DEVICE Vec2 sobol_2d(std::uint64_t pixel, std::uint32_t index, std::uint32_t pair) const {
    const std::uint32_t shuffled = owen_scramble(index, hash(pixel, 3 * pair));
    return {fixed_to_unit(owen_scramble(sobol_dim0(shuffled), hash(pixel, 3 * pair + 1))),
            fixed_to_unit(owen_scramble(sobol_dim1(shuffled), hash(pixel, 3 * pair + 2)))};
  }

  // Sample `index` of pixel (x, y), y counted from the bottom row; `pixel` = y · width + x.
  STRAHL_HOST_DEVICE CameraSample sample(int x, int y, std::uint64_t pixel, std::uint32_t index) const {
    Vec2 film, lens;
    Real time;
    switch (kind) {
      case SamplerKind::Grid:
      case SamplerKind::Stratified: {
        const std::uint32_t count = side * side, k = index % count, round = index / count;
        const bool jitter = kind == SamplerKind::Stratified;
        const auto u = [&](std::uint32_t dim) { return random_real(seed, pixel, index, dim); };
        // Purposes 16 + 4·round + {0, 1, 2}: a new order of the strata each round. The grid's
        // film positions are the strata's centres; lens and time are jittered for both (centres
        // would bias the lens's and the shutter's averages).
        film = stratum_2d(pixel, k, 16 + 4 * round,
                          jitter ? Vec2{u(kDimPixel), u(kDimPixel + 1)} : Vec2{Real(0.5), Real(0.5)});
        lens = stratum_2d(pixel, k, 17 + 4 * round, {u(kDimLens), u(kDimLens + 1)});
        time = stratum_1d(pixel, k, count, 18 + 4 * round, u(kDimTime));
        break;
      }
      case SamplerKind::Random:
        film = {random_real(seed, pixel, index, kDimPixel), random_real(seed, pixel, index, kDimPixel + 1)};
        lens = {random_real(seed, pixel, index, kDimLens), random_real(seed, pixel, index, kDimLens + 1)};
        time = random_real(seed, pixel, index, kDimTime);
        break;
      case SamplerKind::Sobol:
      case SamplerKind::Adaptive:
      default:
        film = sobol_2d(pixel, index, 0);
        lens = sobol_2d(pixel, index, 1);
        time = sobol_2d(pixel, index, 2).x;
        break;
    }
    CameraSample cs;
    cs.film_x = Real(x) + film.x;
    cs.film_y = Real(y) + film.y;
    cs.lens = lens;
    cs.time = time;
    return cs;
  }
};

inline PixelSampler make_pixel_sampler(const SamplingSettings& s) {
  PixelSampler p;
  p.kind = s.sampler;
  p.side = std::uint32_t(strata_side(s.spp));
  p.seed = s.seed;
  return p;
}

}  // namespace strahl
