#pragma once
// The film: camera samples → pixels through a reconstruction filter (sampling/filter.h), as
// weighted sums Σ f·L and Σ f per pixel, resolved to an image on demand (progressive renders,
// checkpoints, the viewer). FilmLayout::add_sample is the one way a sample reaches the image:
// into a tile's buffers (render/tile.h), which Film::merge then adds to the film.
//
// Determinism: a pixel-local filter (box, radius 0.5) adds each sample to its own pixel only, in
// the pixel's sample order, in double precision, continuing the sums the tile carried in: the image
// equals render_pixel() exactly, however passes and tiles split the samples. Wider filters spread a
// sample over neighbouring pixels that other tiles also write; their sums are kept in 64-bit fixed
// point (2^-28 units), whose additions are exact and commute, so a pixel's value does not depend
// on the order in which threads, tiles and ranks deliver the samples. Memory is 32 bytes a pixel,
// plus 24 for the per-pixel statistics where kept, whatever the sample count.

#include <array>
#include <cstdint>
#include <vector>

#include "strahl/camera/camera_sample.h"
#include "strahl/image/image.h"
#include "strahl/math/vec3.h"
#include "strahl/render/film_sample.h"
#include "strahl/render/tile.h"
#include "strahl/sampling/filter.h"
#include "strahl/util/zeroed_array.h"

namespace strahl {

inline double luminance(const Vec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// What a sample needs to know of the film to land in a tile: its size and filter. Small and
// copyable, so a back end away from the film (an MPI worker) makes its own.
class FilmLayout {
 public:
  // `pixel_stats`: keep the per-pixel luminance statistics (adaptive sampling needs them).
  FilmLayout(int width, int height, const Filter& filter, bool pixel_stats = true);

  int width() const { return width_; }
  int height() const { return height_; }
  const Filter& filter() const { return filter_; }
  bool pixel_local() const { return local_; }
  bool keeps_stats() const { return stats_; }
  int margin() const { return margin_; }  // pixels a sample can reach beyond its own
  // The same as plain data, for kernel code (render/film_sample.h; the CUDA back end).
  FilmParams params() const;

  // Sizes the tile's buffers for its rect: no samples taken yet, no wide-filter contributions;
  // sums and statistics it already carries (a request decoded by a worker) are kept, missing ones
  // are zero. Film::begin_tile then carries the film's own sums in.
  void prepare(TileWork& tile) const;
  // A sample of pixel (x, row) (inside the tile) at film position cs.film_x/film_y (raster units,
  // y up from the bottom row, as the pixel sampler made it) with radiance `L`.
  void add_sample(TileWork& tile, int x, int row, const CameraSample& cs, const Vec3& L) const {
    add_pixel_samples(tile, x, row, &cs, &L, 1);
  }
  // add_sample for samples cs[0 … count − 1] of one pixel (x, row), in that order, with the
  // pixel's sums held in registers between them (the same additions). Inline: it runs once per
  // camera sample or packet; the arithmetic is render/film_sample.h's, which the CUDA kernel runs too.
  void add_pixel_samples(TileWork& tile, int x, int row, const CameraSample* cs, const Vec3* L, int count) const {
    const std::size_t own = tile.rect.index(x, row);
    if (stats_)
      for (int j = 0; j < count; ++j) film_add_stats(tile.stats[own], L[j]);
    if (local_) {
      double* const p = &tile.local[own * 4];
      double sums[4] = {p[0], p[1], p[2], p[3]};
      for (int j = 0; j < count; ++j) film_add_local(sums, L[j]);
      p[0] = sums[0], p[1] = sums[1], p[2] = sums[2], p[3] = sums[3];
      return;
    }
    for (int j = 0; j < count; ++j) add_wide(tile, x, row, cs[j], L[j]);
  }

 private:
  void add_wide(TileWork& tile, int x, int row, const CameraSample& cs, const Vec3& L) const;

  int width_, height_;
  Filter filter_;
  bool local_, stats_;
  int margin_;
  Real filter_edge_;  // filter_edge(filter_): the Gaussian's exp once, not per sample
};

class Film {
 public:
  Film(int width, int height, const Filter& filter, bool pixel_stats = true);
  explicit Film(const FilmLayout& layout);

  const FilmLayout& layout() const { return layout_; }
  int width() const { return layout_.width(); }
  int height() const { return layout_.height(); }
  const Filter& filter() const { return layout_.filter(); }
  bool pixel_local() const { return layout_.pixel_local(); }

  // Sizes the tile's buffers and carries in the film's sums and statistics of its pixels (of those with
  // samples to take, when the tile's counts are set: the others are left as they are). Rows whose
  // pixels have no samples so far (tile.first all 0, when set) start from zero without a read: the
  // film holds only what merged tiles took, and tile.first counts those samples.
  void begin_tile(TileWork& tile) const;
  // Takes a rendered tile back: the sums and statistics of its pixels that took samples (taken > 0)
  // replace the film's, its wide-filter contributions are added. Tiles of one pass cover disjoint
  // pixels and may be merged from any threads at once.
  void merge(const TileWork& tile);

  // Σ f·L / Σ f per pixel (0 where the weights sum to 0, e.g. no sample yet). Safe while tiles are
  // being merged (checkpoints, the viewer): each value is read atomically.
  Image resolve() const;

  const PixelStats& stats(int x, int row) const { return stats_.at(index(x, row)); }
  // Every pixel's statistics, row-major from the top (empty unless the layout keeps them).
  const ZeroedArray<PixelStats>& pixel_stats() const { return stats_; }
  // The pixel's Σ f·L (r, g, b) and Σ f, unrounded (tests compare these bit for bit).
  std::array<double, 4> sums(int x, int row) const;

 private:
  std::size_t index(int x, int row) const { return std::size_t(row) * std::size_t(width()) + std::size_t(x); }

  FilmLayout layout_;
  ZeroedArray<double> local_sums_;   // pixel-local filters: r, g, b, weight per pixel
  ZeroedArray<std::int64_t> fixed_;  // wide filters: fixed-point r, g, b, weight per pixel
  ZeroedArray<PixelStats> stats_;
};

}  // namespace strahl
