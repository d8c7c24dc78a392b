#pragma once
// Adaptive sampling (the lecture's "more rays in heterogeneous regions"): after each pass, a
// pixel's error is the relative standard error of its luminance mean,
//
//     e = sqrt(s² / n) / max(mean, 0.01)       (s² the sample variance of its n luminances),
//
// and a pixel keeps refining — its count doubles in the next pass, up to the maximum — while
// e > threshold, or while one of its 8 neighbours does (so that thin features whose first
// samples all missed them, next to pixels that saw them, are sampled too). Every pixel starts with
// the minimum count. Decisions read only the film's per-pixel statistics after a whole pass, so
// they are deterministic.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "strahl/render/film.h"

namespace strahl {

inline double relative_error(const PixelStats& s) {
  if (s.n < 2) return INFINITY;
  const double n = s.n, mean = s.sum / n;
  const double variance = std::max(0.0, (s.sum_sq - s.sum * mean) / (n - 1));
  return std::sqrt(variance / n) / std::max(mean, 0.01);
}

// Samples each pixel gets in the next pass (into `add`, row-major from the top); returns their sum.
inline std::uint64_t plan_adaptive_pass(const Film& film, const std::vector<std::uint32_t>& counts,
                                        std::uint32_t max_spp, double threshold, std::vector<std::uint32_t>& add) {
  const int w = film.width(), h = film.height();
  std::vector<std::uint8_t> over(counts.size(), 0);
  for (int row = 0; row < h; ++row)
    for (int x = 0; x < w; ++x) over[std::size_t(row) * w + x] = relative_error(film.stats(x, row)) > threshold;
  std::uint64_t total = 0;
  for (int row = 0; row < h; ++row)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(row) * w + x;
      bool refine = false;
      for (int dy = -1; dy <= 1 && !refine; ++dy)
        for (int dx = -1; dx <= 1 && !refine; ++dx) {
          const int nx = x + dx, ny = row + dy;
          if (nx >= 0 && nx < w && ny >= 0 && ny < h && over[std::size_t(ny) * w + nx]) refine = true;
        }
      const std::uint32_t c = counts[i];
      add[i] = refine && c < max_spp ? std::min(std::max(c, 1u), max_spp - c) : 0;
      total += add[i];
    }
  return total;
}

}  // namespace strahl
