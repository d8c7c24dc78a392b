#pragma once
// One tile of one pass: the unit of work every back end renders — a CPU thread, an MPI rank, the
// GPU. It carries everything needed to render it away from the film (which pixels, which sample
// numbers, the film's sums so far) and comes back with the new sums, so a back end needs only
// the scene, the pixel sampler and the film's layout (render/film.h).
//
// Why the film's sums travel with the tile: a pixel-local filter sums a pixel's samples in double
// precision in sample order. A tile starts from the pixel's sums so far and continues them, so a
// pixel's value is the same sequence of additions however the samples are split into passes,
// tiles, threads, ranks or devices — bit-identical images for any of them.

#include <cstdint>
#include <vector>

#include "strahl/render/ray_counters.h"

namespace strahl {

// Pixels [x0, x1) × rows [row0, row1), rows counted from the top of the image.
struct TileRect {
  int x0 = 0, row0 = 0, x1 = 0, row1 = 0;

  int width() const { return x1 - x0; }
  int height() const { return row1 - row0; }
  std::size_t pixels() const { return std::size_t(width()) * std::size_t(height()); }
  // Index of pixel (x, row) in the tile's per-pixel arrays (row-major).
  std::size_t index(int x, int row) const { return std::size_t(row - row0) * std::size_t(width()) + std::size_t(x - x0); }
};

// Luminance statistics of a pixel's own samples (for adaptive sampling), in sample order.
struct PixelStats {
  double sum = 0, sum_sq = 0;
  std::uint32_t n = 0;
};

struct TileWork {
  int pass = 0;   // the pass it belongs to (0 first)
  int index = 0;  // its number in the pass's tile grid, row-major
  TileRect rect;
  // Per pixel of rect: take samples first … first + count − 1.
  std::vector<std::uint32_t> first, count;
  // Out: samples taken per pixel — count, or fewer when the render was stopped meanwhile.
  std::vector<std::uint32_t> taken;

  // The film's state (Film::begin_tile fills it, FilmLayout::add_sample adds to it, Film::merge
  // takes back the pixels with taken > 0; a pixel without samples in the pass may hold anything):
  // pixel-local filters: Σ f·L (r, g, b) and Σ f per pixel of rect, carried in and out;
  std::vector<double> local;
  // adaptive sampling: each pixel's statistics, carried in and out (empty when not kept);
  std::vector<PixelStats> stats;
  // wide filters: this tile's own contributions in fixed point (r, g, b, weight) over the rect
  // grown by the filter's reach and clipped to the image, [bx0, bx0 + bw) × [brow0, brow0 + bh).
  int bx0 = 0, brow0 = 0, bw = 0, bh = 0;
  std::vector<std::int64_t> fixed;

  RayCounters counters;

  std::uint64_t samples_taken() const {
    std::uint64_t n = 0;
    for (std::uint32_t t : taken) n += t;
    return n;
  }
};

// Whether every entry of a tile row's counts (n of them) is above 0: then the row's state moves as
// one block.
inline bool all_counted(const std::uint32_t* count, std::size_t n) {
  std::uint32_t none = 0;
  for (std::size_t k = 0; k < n; ++k) none |= std::uint32_t(count[k] == 0);
  return none == 0;
}

// Whether any entry of a tile row's counts is above 0 (most rows of a sparse pass's tile have none).
inline bool any_counted(const std::uint32_t* count, std::size_t n) {
  std::uint32_t any = 0;
  for (std::size_t k = 0; k < n; ++k) any |= count[k];
  return any != 0;
}

// Bit k set where entry k of count[0 … n) (n ≤ 64) is above 0: a loop over a row's pixels with
// samples to take visits them by these bits, past the others without a test each.
inline std::uint64_t counted_bits(const std::uint32_t* count, std::size_t n) {
  std::uint64_t bits = 0;
  for (std::size_t k = 0; k < n; ++k) bits |= std::uint64_t(count[k] != 0) << k;
  return bits;
}

}  // namespace strahl
