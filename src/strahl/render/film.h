#pragma once
// The film: camera samples → pixels through a reconstruction filter (sampling/filter.h), as
// weighted sums Σ f·L and Σ f per pixel, resolved to an image on demand (progressive renders,
// checkpoints). Film::add_sample is the one way a sample reaches the image.
//
// Determinism: a pixel-local filter (box, radius 0.5) adds each sample to its own pixel only, in
// the pixel's sample order, in double precision: the image equals render_pixel() exactly. Wider
// filters spread a sample over neighbouring pixels that other threads also write; their sums are
// kept in 64-bit fixed point (2^-28 units), whose additions are exact and commute, so a pixel's
// value does not depend on the order in which threads and tiles deliver the samples. Memory is
// 32 bytes a pixel, plus 24 for the per-pixel statistics where kept, whatever the sample count.

#include <cstdint>
#include <vector>

#include "strahl/camera/camera_sample.h"
#include "strahl/image/image.h"
#include "strahl/math/vec3.h"
#include "strahl/sampling/filter.h"

namespace strahl {

// Luminance statistics of a pixel's own samples (for adaptive sampling), in sample order.
struct PixelStats {
  double sum = 0, sum_sq = 0;
  std::uint32_t n = 0;
};

inline double luminance(const Vec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

class Film {
 public:
  // The part of the film one tile writes: pixels [x0, x1) × rows [row0, row1); for wide filters a
  // private fixed-point buffer over the tile and its filter margin, added to the film at the end.
  struct Tile {
    int x0 = 0, row0 = 0, x1 = 0, row1 = 0;
    int bx0 = 0, brow0 = 0, bw = 0, bh = 0;
    std::vector<std::int64_t> sums;  // bw · bh · 4 (r, g, b, weight)
  };

  // `pixel_stats`: keep the per-pixel luminance statistics (adaptive sampling needs them).
  Film(int width, int height, const Filter& filter, bool pixel_stats = true);

  int width() const { return width_; }
  int height() const { return height_; }
  const Filter& filter() const { return filter_; }
  bool pixel_local() const { return local_; }

  Tile begin_tile(int x0, int row0, int x1, int row1) const;
  // A sample of pixel (x, row) (inside the tile) at film position cs.film_x/film_y (raster units,
  // y up from the bottom row, as the pixel sampler made it) with radiance `L`.
  void add_sample(Tile& tile, int x, int row, const CameraSample& cs, const Vec3& L);
  void end_tile(Tile& tile);

  // Σ f·L / Σ f per pixel (0 where the weights sum to 0, e.g. no sample yet). Safe while tiles are being added
  // (checkpoints): each value is read atomically, a pixel may be between two samples.
  Image resolve() const;

  const PixelStats& stats(int x, int row) const { return stats_.at(index(x, row)); }

 private:
  std::size_t index(int x, int row) const { return std::size_t(row) * std::size_t(width_) + std::size_t(x); }

  int width_, height_;
  Filter filter_;
  bool local_;
  int margin_;                       // pixels a sample can reach beyond its own
  std::vector<double> local_sums_;   // pixel-local filters: r, g, b, weight per pixel
  std::vector<std::int64_t> fixed_;  // wide filters: fixed-point r, g, b, weight per pixel
  std::vector<PixelStats> stats_;
};

}  // namespace strahl
