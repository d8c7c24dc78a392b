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

// The film positions of N Sobol samples, lane i sample index[i] of the pixel at (px[i], py[i])
// with film-pair scrambles s0[i], s1[i], s2[i] (PixelSequence::h[0 … 2]): PixelSequence::sample()'s,
// the lanes side by side, with lens (0.5, 0.5) and time 0 (PixelSequence::samples() sets those
// where the camera uses them).
template <int N>
STRAHL_HOST_DEVICE inline void sobol_film_lanes(const std::uint32_t* __restrict index, const std::uint32_t* __restrict s0,
                                                const std::uint32_t* __restrict s1, const std::uint32_t* __restrict s2,
                                                const Real* __restrict px, const Real* __restrict py, CameraSample* cs,
                                                FilmLanes<N>& __restrict film) {
  for (int i = 0; i < N; ++i) {
    std::uint32_t a, b;
    sobol_pair(index[i], s0[i], s1[i], s2[i], a, b);
    film.x[i] = px[i] + fixed_to_unit(a);
    film.y[i] = py[i] + fixed_to_unit(b);
    film.time[i] = 0;
  }
  film.get(cs);
}

// The lens positions (unit square) and shutter times of N Sobol samples, beside
// sobol_film_lanes()'s film positions: lane i is sample index[i], scrambled by scramble[0 … 2][i]
// for the lens's pair (PixelSequence::h[3 … 5]) and scramble[3 … 5][i] for the shutter's (h[6 … 8])
// — sample()'s arithmetic, the lanes side by side, into cs[0 … N) and film.time.
template <int N>
STRAHL_HOST_DEVICE inline void sobol_lens_time_lanes(bool lens, bool time, const std::uint32_t* __restrict index,
                                                     const std::uint32_t (&scramble)[6][N], CameraSample* cs,
                                                     FilmLanes<N>& __restrict film) {
  if (lens)
    for (int i = 0; i < N; ++i) {
      std::uint32_t a, b;
      sobol_pair(index[i], scramble[0][i], scramble[1][i], scramble[2][i], a, b);
      cs[i].lens = Vec2{fixed_to_unit(a), fixed_to_unit(b)};
    }
  if (time)
    for (int i = 0; i < N; ++i) {
      std::uint32_t a, b;
      sobol_pair(index[i], scramble[3][i], scramble[4][i], scramble[5][i], a, b);
      film.time[i] = cs[i].time = fixed_to_unit(a);
    }
}

// Lane i: the stratum (of n = side² > 1, side no power of two) of sample index[i] in the order
// order[i] of its round: permutation_element(index[i] % n, n, order[i]), the lanes side by side.
template <int N>
STRAHL_HOST_DEVICE inline void strata_of_lanes(std::uint32_t n, const std::uint32_t* __restrict index,
                                               const std::uint32_t* __restrict order, std::uint32_t* __restrict s) {
  const double d = double(n), inv = 1 / d;
  std::uint32_t k[N];
  for (int i = 0; i < N; ++i) {
    std::uint32_t round;
    divide_exactly(index[i], d, inv, round, k[i]);
  }
  permutation_elements<N>(k, n, order, s);
}

// Lane i: the point in [0, 1)² of sample index[i] of a grid or stratified sequence — its stratum
// in the order order[i] of its round (PixelSequence::strata_order), jittered by dimensions dim,
// dim + 1 of the random numbers keyed by stream[i] or at the stratum's centre (`jitter` false:
// the grid's film positions) — into (ux[i], uy[i]): PixelSequence::stratum_2d()'s arithmetic,
// the lanes side by side. side_shift: log2(side) for a power of two (shifts and masks, no walk),
// else −1 (strata_of_lanes; the row and column by divide_exactly).
template <int N>
STRAHL_HOST_DEVICE inline void strata_lanes_2d(bool jitter, std::uint32_t side, int side_shift, std::uint32_t dim,
                                               const std::uint32_t* __restrict index,
                                               const std::uint32_t* __restrict order,
                                               const std::uint64_t* __restrict stream, Real* __restrict ux,
                                               Real* __restrict uy) {
  const std::uint32_t n = side * side;
  std::uint32_t s[N];  // the lanes' strata (permutation_element_pow2 of [0, 1) is 0)
  if (side_shift >= 0) {
    for (int i = 0; i < N; ++i) s[i] = permutation_element_pow2(index[i] & (n - 1), n, order[i]);
  } else {
    strata_of_lanes<N>(n, index, order, s);
  }
  Real jx[N], jy[N];
  if (jitter) {
    for (int i = 0; i < N; ++i) {
      jx[i] = to_unit(keyed_bits(stream[i], index[i], dim));
      jy[i] = to_unit(keyed_bits(stream[i], index[i], dim + 1));
    }
  } else {
    for (int i = 0; i < N; ++i) jx[i] = jy[i] = Real(0.5);
  }
  if (side_shift >= 0) {
    const Real inv = Real(1) / Real(side);  // exact: a power of two (1 for one stratum: (0 + j) · 1 = j)
    for (int i = 0; i < N; ++i) {
      ux[i] = (Real(s[i] & (side - 1)) + jx[i]) * inv;
      uy[i] = (Real(s[i] >> side_shift) + jy[i]) * inv;
    }
  } else {
    const double d = double(side), inv = 1 / d;
    for (int i = 0; i < N; ++i) {
      std::uint32_t row, column;
      divide_exactly(s[i], d, inv, row, column);
      ux[i] = (Real(column) + jx[i]) / Real(side);
      uy[i] = (Real(row) + jy[i]) / Real(side);
    }
  }
}

// The film positions of N grid or stratified samples, with lens (0.5, 0.5) and time 0
// (strata_lens_time_lanes() sets those where the camera uses them): lane i is sample index[i] of
// the pixel at (px[i], py[i]), its film stratum in order order[i] (strata_lanes_2d). `jitter`:
// stratified (else the strata's centres, the grid).
template <int N>
STRAHL_HOST_DEVICE inline void strata_film_lanes(bool jitter, std::uint32_t side, int side_shift,
                                                 const std::uint32_t* __restrict index,
                                                 const std::uint32_t* __restrict order,
                                                 const std::uint64_t* __restrict stream, const Real* __restrict px,
                                                 const Real* __restrict py, CameraSample* cs,
                                                 FilmLanes<N>& __restrict film) {
  Real ux[N], uy[N];
  strata_lanes_2d<N>(jitter, side, side_shift, kDimPixel, index, order, stream, ux, uy);
  for (int i = 0; i < N; ++i) {
    film.x[i] = px[i] + ux[i];
    film.y[i] = py[i] + uy[i];
    film.time[i] = 0;
  }
  film.get(cs);
}

// The lens positions (unit square) and shutter times of the same samples, beside
// strata_film_lanes(): the lens's strata in orders lens_order[i], the shutter's in time_order[i]
// (PixelSequence::strata_order, purposes 1 and 2), both jittered — sample()'s arithmetic, the
// lanes side by side, into cs[0 … N) and film.time.
template <int N>
STRAHL_HOST_DEVICE inline void strata_lens_time_lanes(bool lens, bool time, std::uint32_t side, int side_shift,
                                                      const std::uint32_t* __restrict index,
                                                      const std::uint32_t* __restrict lens_order,
                                                      const std::uint32_t* __restrict time_order,
                                                      const std::uint64_t* __restrict stream, CameraSample* cs,
                                                      FilmLanes<N>& __restrict film) {
  if (lens) {
    Real ux[N], uy[N];
    strata_lanes_2d<N>(true, side, side_shift, kDimLens, index, lens_order, stream, ux, uy);
    for (int i = 0; i < N; ++i) cs[i].lens = Vec2{ux[i], uy[i]};
  }
  if (time) {
    const std::uint32_t n = side * side;
    std::uint32_t s[N];
    if (side_shift >= 0) {
      for (int i = 0; i < N; ++i) s[i] = permutation_element_pow2(index[i] & (n - 1), n, time_order[i]);
    } else {
      strata_of_lanes<N>(n, index, time_order, s);
    }
    for (int i = 0; i < N; ++i) {
      const Real t = Real(s[i]) + to_unit(keyed_bits(stream[i], index[i], kDimTime));
      film.time[i] = side_shift >= 0 ? t * (Real(1) / Real(n)) : t / Real(n);  // 1/n exact for powers of two
      cs[i].time = film.time[i];
    }
  }
}

// The samples of one pixel, with the pixel's hashes (permutation and scrambling seeds) computed
// once rather than per sample.
struct PixelSequence {
  SamplerKind kind = SamplerKind::Grid;
  std::uint32_t side = 1;
  // log2(side) when side is a power of two (1, 2, 4, 8, …), else −1: the strata's row and column
  // and the sample's round then come by shifts and masks instead of integer divisions, and the
  // divisions by side by multiplications with its exact reciprocal (the same values, bit for bit).
  int side_shift = 0;
  std::uint64_t seed = 0, pixel = 0, key = 0;  // key: what hash() mixes (0 when no hash is needed)
  std::uint64_t stream = 0;  // pixel_key(seed, pixel): the per-sample random numbers are keyed_bits(stream, …)
  std::uint64_t seed_mix = 0;  // mix_seed(seed): pixel_key()'s part that depends on the seed alone
  std::uint32_t needed = 0;    // bit i: h[i] is used (PixelSampler::sequence)
  int x = 0, y = 0;
  // Grid/stratified: round 0's film, lens, time orders; sobol: 3 per pair; 0 where unused. Left
  // unset by `PixelSequence p;` (PixelSampler::pixel sets it: zeroing it per pixel cost a `rep
  // stos`), zero in `PixelSequence{}`.
  std::uint32_t h[9];
  // Whether the camera uses the lens and time dimensions (a thin lens, an open shutter). When it
  // does not, sample() leaves them at lens (0.5, 0.5) and time 0 without computing them; the film
  // positions are the same either way (each dimension has its own random numbers and orders).
  bool uses_lens = true, uses_time = true;

  // A 32-bit hash per (pixel, purpose), independent of the per-sample random numbers.
  STRAHL_HOST_DEVICE std::uint32_t hash(std::uint32_t purpose) const {
    return std::uint32_t(mix64(key + (std::uint64_t(purpose) + 1) * 0x9e3779b97f4a7c15ULL) >> 32);
  }

  // Grid and stratified: the round of sample `index` (each round visits the side² strata once).
  STRAHL_HOST_DEVICE std::uint32_t strata_round(std::uint32_t index) const {
    if (side_shift >= 0) return index >> (2 * side_shift);
    const std::uint32_t n = side * side;
    return index < n ? 0 : index / n;  // (most samples are in round 0: no division)
  }
  // Grid and stratified: the order in which the round of sample `index` visits the film's strata
  // (purpose 0), the lens's (1) or the shutter's (2) — sample()'s order(purpose); 0 for one
  // stratum, which needs no order.
  STRAHL_HOST_DEVICE std::uint32_t strata_order(std::uint32_t index, std::uint32_t purpose = 0) const {
    if (side <= 1) return 0;
    const std::uint32_t round = strata_round(index);
    return round == 0 ? h[purpose] : hash(3 * round + purpose);
  }
  // Whether this sequence's samples come from strata_film_lanes() and strata_lens_time_lanes()
  // (else sobol's lanes or sample() by sample).
  STRAHL_HOST_DEVICE bool strata_lanes() const {
    return kind == SamplerKind::Grid || kind == SamplerKind::Stratified;
  }

  STRAHL_HOST_DEVICE Vec2 stratum_2d(std::uint32_t k, std::uint32_t order, Vec2 jitter) const {
    if (side == 1) return jitter;  // (0 + j) / 1, without the divisions
    const std::uint32_t s = permutation_element(k, side * side, order);
    if (side_shift >= 0) {
      const Real inv = Real(1) / Real(side);  // exact: a power of two
      return {(Real(s & (side - 1)) + jitter.x) * inv, (Real(s >> side_shift) + jitter.y) * inv};
    }
    return {(Real(s % side) + jitter.x) / Real(side), (Real(s / side) + jitter.y) / Real(side)};
  }
  STRAHL_HOST_DEVICE Vec2 sobol_2d(std::uint32_t index, std::uint32_t pair) const {
    std::uint32_t a, b;
    sobol_pair(index, h[3 * pair], h[3 * pair + 1], h[3 * pair + 2], a, b);
    return {fixed_to_unit(a), fixed_to_unit(b)};
  }

  // Sample number `index` of the pixel.
  STRAHL_HOST_DEVICE CameraSample sample(std::uint32_t index) const {
    Vec2 film, lens{Real(0.5), Real(0.5)};
    Real time = 0;
    switch (kind) {
      case SamplerKind::Grid:
      case SamplerKind::Stratified: {
        const std::uint32_t count = side * side;
        const bool pow2 = side_shift >= 0;
        const std::uint32_t k = count == 1 ? 0 : pow2 ? index & (count - 1) : index % count;
        const bool jitter = kind == SamplerKind::Stratified;
        const auto u = [&](std::uint32_t dim) { return to_unit(keyed_bits(stream, index, dim)); };
        // Each round visits the strata in new orders (strata_order: purposes 3·round + {0, 1, 2});
        // one stratum needs no order (and pixel() computed no hashes for it). The grid's film
        // positions are the strata's centres; lens and time are jittered for both (centres would
        // bias the lens's and the shutter's averages).
        const auto order = [&](std::uint32_t purpose) { return strata_order(index, purpose); };
        film = stratum_2d(k, order(0), jitter ? Vec2{u(kDimPixel), u(kDimPixel + 1)} : Vec2{Real(0.5), Real(0.5)});
        if (uses_lens) lens = stratum_2d(k, order(1), {u(kDimLens), u(kDimLens + 1)});
        if (uses_time) {
          const Real t = Real(permutation_element(k, count, order(2))) + u(kDimTime);
          time = pow2 ? t * (Real(1) / Real(count)) : t / Real(count);  // 1/count exact for powers of two
        }
        break;
      }
      case SamplerKind::Random: {
        const auto u = [&](std::uint32_t dim) { return to_unit(keyed_bits(stream, index, dim)); };
        film = {u(kDimPixel), u(kDimPixel + 1)};
        if (uses_lens) lens = {u(kDimLens), u(kDimLens + 1)};
        if (uses_time) time = u(kDimTime);
        break;
      }
      case SamplerKind::Sobol:
      case SamplerKind::Adaptive:
      default:
        film = sobol_2d(index, 0);
        if (uses_lens) lens = sobol_2d(index, 1);
        if (uses_time) time = sobol_2d(index, 2).x;
        break;
    }
    CameraSample cs;
    cs.film_x = Real(x) + film.x;
    cs.film_y = Real(y) + film.y;
    cs.lens = lens;
    cs.time = time;
    return cs;
  }

  // sample(first + i) for i < count (≤ N) into cs[0 … N), their film positions and times into
  // `film` too (padded: FilmLanes::pad): for grid, stratified and sobol with the lanes side by
  // side (sample()'s arithmetic; cs[count …] get positions nobody reads); sample by sample
  // otherwise.
  template <int N>
  STRAHL_HOST_DEVICE void samples(std::uint32_t first, int count, CameraSample* cs, FilmLanes<N>& film) const {
    if (strata_lanes() && count > 0) {
      std::uint32_t index[N], order[3][N];  // the film's, the lens's and the shutter's orders
      std::uint64_t streams[N];
      Real px[N], py[N];
      const int purposes = uses_time ? 3 : uses_lens ? 2 : 1;
      for (int k = 0; k < purposes; ++k) {
        const std::uint32_t first_order = strata_order(first, std::uint32_t(k));
        for (int i = 0; i < N; ++i) order[k][i] = first_order;
      }
      for (int i = 0; i < N; ++i) {
        index[i] = first + std::uint32_t(i), streams[i] = stream;
        px[i] = Real(x), py[i] = Real(y);
      }
      const std::uint32_t last = first + std::uint32_t(count) - 1;
      if (side > 1 && strata_round(last) != strata_round(first))  // the samples start a new round
        for (int k = 0; k < purposes; ++k)
          for (int i = 1; i < count; ++i) order[k][i] = strata_order(index[i], std::uint32_t(k));
      strata_film_lanes<N>(kind == SamplerKind::Stratified, side, side_shift, index, order[0], streams, px, py, cs, film);
      if (uses_lens || uses_time)
        strata_lens_time_lanes<N>(uses_lens, uses_time, side, side_shift, index, order[1], order[2], streams, cs, film);
      film.pad(count);
      return;
    }
    if (kind == SamplerKind::Sobol || kind == SamplerKind::Adaptive) {
      std::uint32_t index[N], s0[N], s1[N], s2[N];
      Real px[N], py[N];
      for (int i = 0; i < N; ++i) {
        index[i] = first + std::uint32_t(i), s0[i] = h[0], s1[i] = h[1], s2[i] = h[2];
        px[i] = Real(x), py[i] = Real(y);
      }
      sobol_film_lanes<N>(index, s0, s1, s2, px, py, cs, film);
      if (uses_lens || uses_time) {
        std::uint32_t scramble[6][N];
        for (int k = 0; k < 6; ++k)
          for (int i = 0; i < N; ++i) scramble[k][i] = h[3 + k];
        sobol_lens_time_lanes<N>(uses_lens, uses_time, index, scramble, cs, film);
      }
      film.pad(count);
      return;
    }
    for (int i = 0; i < count; ++i) cs[i] = sample(first + std::uint32_t(i));
    film.set(cs, count);
  }
};

// Kernel side: the sampler's settings, plain data.
struct PixelSampler {
  SamplerKind kind = SamplerKind::Grid;
  std::uint32_t side = 1;  // grid/stratified: n
  std::uint64_t seed = 0;

  // The samples of pixel (x, y), y counted from the bottom row; `pixel` = y · width + x. Without
  // `uses_lens` / `uses_time` the sequence leaves those dimensions at lens (0.5, 0.5) and time 0,
  // and their hashes are not computed (h[] holds 0 there).
  STRAHL_HOST_DEVICE PixelSequence pixel(int x, int y, std::uint64_t pixel_index, bool uses_lens = true,
                                         bool uses_time = true) const {
    PixelSequence p = sequence(uses_lens, uses_time);
    place(p, x, y, pixel_index);
    return p;
  }

  // pixel() in two steps, for a loop over many pixels: what every pixel's sequence shares (the
  // sampler's settings, which hashes it needs; h[] 0 where it needs none) …
  STRAHL_HOST_DEVICE PixelSequence sequence(bool uses_lens = true, bool uses_time = true) const {
    PixelSequence p;  // (h[] is set below: no block of zeros first)
    p.kind = kind;
    p.side = side;
    p.side_shift = -1;
    for (int b = 0; b < 16 && p.side_shift < 0; ++b)
      if (side == (1u << b)) p.side_shift = b;
    p.seed = seed;
    p.seed_mix = mix_seed(seed);
    // Hashes: the sobol pairs' scrambles, or the strata orders (none for a single stratum).
    const int hashes = kind == SamplerKind::Random                                  ? 0
                       : (kind == SamplerKind::Sobol || kind == SamplerKind::Adaptive) ? 9
                       : side > 1                                                     ? 3
                                                                                      : 0;
    p.uses_lens = uses_lens;
    p.uses_time = uses_time;
    // Hash i serves the film (sobol: pair 0, hashes 0–2; strata: order 0), the lens (pair 1; order
    // 1) or the time (pair 2; order 2); 0 where not needed.
    p.needed = 0;
    for (int i = 0; i < 9; ++i) {
      const int use = hashes == 9 ? i / 3 : i;
      if (i < hashes && !(use == 1 && !uses_lens) && !(use == 2 && !uses_time)) p.needed |= 1u << i;
      p.h[i] = 0;
    }
    return p;
  }
  // … and what is the pixel's own: its place, its random-number key, its hashes.
  STRAHL_HOST_DEVICE static void place(PixelSequence& p, int x, int y, std::uint64_t pixel_index) {
    p.pixel = pixel_index;
    p.x = x;
    p.y = y;
    // pixel_key(seed, pixel); sample index 0xffffffff, which no sample reaches, for the hashes'
    // key: independent of the samples' numbers.
    p.stream = pixel_key_of(p.seed_mix, pixel_index);
    p.key = p.needed == 0 ? 0 : keyed_bits(p.stream, 0xffffffffu, 0);
    for (int i = 0; i < 9; ++i)
      if ((p.needed >> i) & 1u) p.h[i] = p.hash(std::uint32_t(i));
  }

  // Sample `index` of pixel (x, y) (tests; the render loop keeps the PixelSequence).
  STRAHL_HOST_DEVICE CameraSample sample(int x, int y, std::uint64_t pixel_index, std::uint32_t index) const {
    return pixel(x, y, pixel_index).sample(index);
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
