#pragma once
// Adaptive sampling (the lecture's "more rays in heterogeneous regions"): after each pass, a
// pixel's error is the relative standard error of its luminance mean,
//
//     e = sqrt(s² / n) / max(mean, 0.01)       (s² the sample variance of its n luminances),
//
// and a pixel keeps refining — its count doubles in the next pass, up to the maximum — while
// e > threshold, or while one of its 8 neighbours does (so that thin features whose first
// samples all missed them, next to pixels that saw them, are sampled too). Every pixel starts with
// the minimum count. A pixel with a single sample has no variance to go by; there its neighbours'
// samples stand in for more of its own (the edge detection of POV-Ray's adaptive anti-aliasing):
//
//     e = max over the 8 neighbours j with samples of |mean − mean_j| / max(mean, 0.01),
//
// so `adaptive_min 1` spends one sample on flat regions and refines where the image changes.
// Decisions read only the film's per-pixel statistics after a whole pass, so they are deterministic.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "strahl/render/film.h"

namespace strahl {

inline double relative_error(const PixelStats& s) {
  if (s.n < 2) return INFINITY;
  const double n = s.n, mean = s.sum / n;
  const double variance = std::max(0.0, (s.sum_sq - s.sum * mean) / (n - 1));
  return std::sqrt(variance / n) / std::max(mean, 0.01);
}

// The error of a pixel with one sample (x, row): its largest relative contrast to a neighbour.
inline double contrast_error(const Film& film, int x, int row) {
  const PixelStats& s = film.stats(x, row);
  const double mean = s.sum / s.n;
  double e = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = x + dx, ny = row + dy;
      if ((dx == 0 && dy == 0) || nx < 0 || nx >= film.width() || ny < 0 || ny >= film.height()) continue;
      const PixelStats& o = film.stats(nx, ny);
      if (o.n > 0) e = std::max(e, std::abs(mean - o.sum / o.n));
    }
  return e / std::max(mean, 0.01);
}

inline double pixel_error(const Film& film, int x, int row) {
  const PixelStats& s = film.stats(x, row);
  return s.n == 1 ? contrast_error(film, x, row) : relative_error(s);
}

// Samples each pixel gets in the next pass (into `add`, row-major from the top); returns their sum.
// A pixel refines when it or one of its 8 neighbours is over the threshold, and it has fewer than
// max_spp samples: it doubles its count (at least 1 more), up to max_spp.
//
// The plan of a pass changes only near the pixels the previous pass sampled: a pixel's error reads
// its own and its neighbours' statistics, its decision its own and its neighbours' errors. So the
// planner keeps every pixel's error flag and the counts it last saw, and re-examines only pixels
// within two of a pixel whose count changed; every other pixel was not refined last time and is
// not now (had it been, its count would have changed). The answers are those of examining every
// pixel every pass (AdaptivePlanner.IncrementalPlanEqualsAFullPlan), at a cost that follows the
// samples taken rather than the image size — the late passes refine a few dozen pixels.
//
// Between two calls the caller takes at most the samples planned (counts change only at the
// pixels of planned()) and leaves `add` as it was or zeroes entries: the planner then looks only
// at the pixels it planned, and clears only the entries it set (no pass over the whole image).
class AdaptivePlanner {
 public:
  // `full`: examine every pixel (what the incremental plan must equal; tests).
  // `headroom`, where given, receives Σ (max_spp − counts[p]) over the pixels planned more samples.
  std::uint64_t plan(const Film& film, std::span<const std::uint32_t> counts, std::uint32_t max_spp,
                     double threshold, std::vector<std::uint32_t>& add, bool full = false,
                     std::uint64_t* headroom = nullptr) {
    const int w = film.width(), h = film.height();
    const std::size_t n = counts.size();
    if (seen_.size() != n || add.size() != n || full) {
      add.resize(n);
      if (seen_.size() != n) {  // fresh pages, first touched by plan_every_pixel's threads
        seen_ = ZeroedArray<std::uint32_t>(n);
        over_ = ZeroedArray<std::uint8_t>(n);
        mark_ = ZeroedArray<std::uint8_t>(n);
        near_ = ZeroedArray<std::uint8_t>(n);
      }
      return plan_every_pixel(film, counts, max_spp, threshold, add, headroom);  // (sets seen_, over_)
    }
    // mark_ of the pixels next to a change 2 (their errors are recomputed), of the pixels next to
    // those 1 (their decisions are taken again); touched_ lists them, to clear them afterwards.
    // Only the pixels planned last time can have changed.
    touched_.clear();
    changed_.clear();
    for (const std::uint32_t p : planned_) {
      if (counts[p] != seen_[p]) changed_.push_back(p);
      add[p] = 0;
    }
    if (changed_.size() > n / 32) return plan_every_pixel(film, counts, max_spp, threshold, add, headroom);
    // The 3×3 neighbourhood of a pixel away from the image's edges, row by row.
    const std::ptrdiff_t sw = w;
    const std::ptrdiff_t nine[9] = {-sw - 1, -sw, -sw + 1, -1, 0, 1, sw - 1, sw, sw + 1};
    const auto around = [&](std::size_t p, std::uint8_t level) {
      const int x = int(p % std::size_t(w)), row = int(p / std::size_t(w));
      if (x > 0 && x + 1 < w && row > 0 && row + 1 < h) {
        for (const std::ptrdiff_t d : nine) {
          const std::size_t q = std::size_t(std::ptrdiff_t(p) + d);
          if (mark_[q] == 0) touched_.push_back(std::uint32_t(q));
          if (mark_[q] < level) mark_[q] = level;
        }
        return;
      }
      for (int ny = std::max(0, row - 1); ny <= std::min(h - 1, row + 1); ++ny)
        for (int nx = std::max(0, x - 1); nx <= std::min(w - 1, x + 1); ++nx) {
          const std::size_t q = std::size_t(ny) * std::size_t(w) + std::size_t(nx);
          if (mark_[q] == 0) touched_.push_back(std::uint32_t(q));
          if (mark_[q] < level) mark_[q] = level;
        }
    };
    for (const std::uint32_t p : changed_) {
      seen_[p] = counts[p];
      around(p, 2);
    }
    const std::size_t next_to_change = touched_.size();
    for (std::size_t k = 0; k < next_to_change; ++k) {
      const std::size_t p = touched_[k];
      if (mark_[p] != 2) continue;
      over_[p] = pixel_error(film, int(p % std::size_t(w)), int(p / std::size_t(w))) > threshold;
      around(p, 1);
    }
    // Pixels not touched were not refined last time (their counts did not change) and nothing near
    // them changed: they are not refined now (their entries of `add` are 0: see above).
    std::uint64_t total = 0, room = 0;
    planned_.clear();
    for (const std::uint32_t p : touched_) {
      mark_[p] = 0;
      const int x = int(p % std::uint32_t(w)), row = int(p / std::uint32_t(w));
      if (x > 0 && x + 1 < w && row > 0 && row + 1 < h) {  // more(), away from the edges
        std::uint8_t any = 0;
        for (const std::ptrdiff_t d : nine) any |= over_[std::size_t(std::ptrdiff_t(p) + d)];
        const std::uint32_t c = counts[p];
        add[p] = doubled(any != 0, c, max_spp);
      } else {
        add[p] = more(x, row, w, h, counts[p], max_spp);
      }
      if (add[p] == 0) continue;
      planned_.push_back(p);
      total += add[p];
      room += max_spp - counts[p];
    }
    if (headroom != nullptr) *headroom = room;
    return total;
  }

  // The pixels the last plan gave samples (add > 0), in no particular order.
  const std::vector<std::uint32_t>& planned() const { return planned_; }

 private:
  // The samples pixel (x, row), which has c, takes next: it doubles its count (at least 1 more, at
  // most up to max_spp) when it or one of its 8 neighbours is over the threshold.
  std::uint32_t more(int x, int row, int w, int h, std::uint32_t c, std::uint32_t max_spp) const {
    bool refine = false;
    for (int ny = std::max(0, row - 1); ny <= std::min(h - 1, row + 1) && !refine; ++ny)
      for (int nx = std::max(0, x - 1); nx <= std::min(w - 1, x + 1) && !refine; ++nx)
        refine = over_[std::size_t(ny) * std::size_t(w) + std::size_t(nx)] != 0;
    return doubled(refine, c, max_spp);
  }
  // The samples a pixel with c takes next when it refines: its count doubled (at least 1 more, at
  // most up to max_spp); none when it does not.
  // (Without branches: plan_every_pixel's loop over a row is vectorised.)
  static std::uint32_t doubled(bool refine, std::uint32_t c, std::uint32_t max_spp) {
    return (refine & (c < max_spp)) ? std::min(std::max(c, 1u), max_spp - c) : 0u;
  }

  // The plan when much changed (the first pass): every error, then every decision — pixel_error()
  // and more() for every pixel, computed row by row in bands of rows on all threads (each pixel's
  // answer depends only on the film, so it is the same for any split): each pixel's mean divided out
  // once (NaN where a pixel has no sample: std::max never takes it), and the 3×3 neighbourhoods read
  // with the image's edge rows and columns standing in for those beyond it (which only repeats a
  // neighbour, or the pixel itself, whose contrast to itself is 0). render/adaptive.cpp.
  std::uint64_t plan_every_pixel(const Film& film, std::span<const std::uint32_t> counts, std::uint32_t max_spp,
                                 double threshold, std::vector<std::uint32_t>& add, std::uint64_t* headroom);

  ZeroedArray<std::uint32_t> seen_;  // the counts at the last plan
  ZeroedArray<std::uint8_t> over_;   // error > threshold, as of the last plan
  ZeroedArray<std::uint8_t> mark_;   // all 0 between plans
  ZeroedArray<std::uint8_t> near_;   // plan_every_pixel: over_ of a pixel or its row neighbours
  std::vector<std::uint32_t> touched_;
  std::vector<std::uint32_t> changed_;  // the pixels whose counts changed since the last plan
  std::vector<std::uint32_t> planned_;  // the pixels the last plan gave samples
  // plan_every_pixel: each band's planned pixels and sums (joined in band order).
  struct Band {
    std::vector<std::uint32_t> planned;
    std::uint64_t total = 0, room = 0;
  };
  std::vector<Band> bands_;
};

}  // namespace strahl
