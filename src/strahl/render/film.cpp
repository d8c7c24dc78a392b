#include "strahl/render/film.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace strahl {

namespace {

constexpr double kFixedScale = 268435456.0;  // 2^28 units per 1
// Larger contributions are clamped so that sums of many stay far from int64 overflow.
constexpr double kFixedLimit = 1e6;

std::int64_t to_fixed(double v) {
  return std::llround(std::clamp(v, -kFixedLimit, kFixedLimit) * kFixedScale);
}

}  // namespace

Film::Film(int width, int height, const Filter& filter, bool pixel_stats)
    : width_(width),
      height_(height),
      filter_(filter),
      local_(filter_is_pixel_local(filter)),
      margin_(int(std::ceil(filter.radius)) + 1),
      stats_(pixel_stats ? std::size_t(width) * std::size_t(height) : 0) {
  const std::size_t n = std::size_t(width) * std::size_t(height) * 4;
  if (local_)
    local_sums_.assign(n, 0.0);
  else
    fixed_.assign(n, 0);
}

Film::Tile Film::begin_tile(int x0, int row0, int x1, int row1) const {
  Tile t;
  t.x0 = x0;
  t.row0 = row0;
  t.x1 = x1;
  t.row1 = row1;
  if (!local_) {
    t.bx0 = std::max(0, x0 - margin_);
    t.brow0 = std::max(0, row0 - margin_);
    t.bw = std::min(width_, x1 + margin_) - t.bx0;
    t.bh = std::min(height_, row1 + margin_) - t.brow0;
    t.sums.assign(std::size_t(t.bw) * std::size_t(t.bh) * 4, 0);
  }
  return t;
}

void Film::add_sample(Tile& tile, int x, int row, const CameraSample& cs, const Vec3& L) {
  const std::size_t own = index(x, row);
  if (!stats_.empty()) {
    PixelStats& st = stats_[own];
    const double lum = luminance(L);
    st.sum += lum;
    st.sum_sq += lum * lum;
    ++st.n;
  }

  if (local_) {
    // Only this tile's thread writes the pixel; atomic stores let resolve() read meanwhile.
    double* p = &local_sums_[own * 4];
    const double add[4] = {L.x, L.y, L.z, 1.0};
    for (int c = 0; c < 4; ++c) std::atomic_ref<double>(p[c]).store(p[c] + add[c], std::memory_order_relaxed);
    return;
  }

  // Pixels (px, py) (py counted from the bottom) whose centre lies within the filter's support.
  const Real r = filter_.radius;
  const int y = height_ - 1 - row;
  Real wx[16], wy[16];
  const int px0 = std::max(std::max(0, x - margin_), int(std::floor(cs.film_x - Real(0.5) - r)));
  const int px1 = std::min(std::min(width_ - 1, x + margin_), int(std::ceil(cs.film_x - Real(0.5) + r)));
  const int py0 = std::max(std::max(0, y - margin_), int(std::floor(cs.film_y - Real(0.5) - r)));
  const int py1 = std::min(std::min(height_ - 1, y + margin_), int(std::ceil(cs.film_y - Real(0.5) + r)));
  for (int px = px0; px <= px1; ++px) wx[px - px0] = filter_1d(filter_, cs.film_x - (Real(px) + Real(0.5)));
  for (int py = py0; py <= py1; ++py) wy[py - py0] = filter_1d(filter_, cs.film_y - (Real(py) + Real(0.5)));
  for (int py = py0; py <= py1; ++py) {
    if (wy[py - py0] == 0) continue;
    const int prow = height_ - 1 - py;
    for (int px = px0; px <= px1; ++px) {
      const Real w = wx[px - px0] * wy[py - py0];
      if (w == 0) continue;
      std::int64_t* p =
          &tile.sums[(std::size_t(prow - tile.brow0) * std::size_t(tile.bw) + std::size_t(px - tile.bx0)) * 4];
      // The weight quantised first and the values weighted by the quantised weight: a flat
      // image then resolves to its value up to the rounding of each product.
      const std::int64_t qw = to_fixed(w);
      const double fw = double(qw) / kFixedScale;
      p[0] += to_fixed(fw * L.x);
      p[1] += to_fixed(fw * L.y);
      p[2] += to_fixed(fw * L.z);
      p[3] += qw;
    }
  }
}

void Film::end_tile(Tile& tile) {
  if (local_) return;
  for (int r = 0; r < tile.bh; ++r)
    for (int c = 0; c < tile.bw; ++c) {
      const std::int64_t* src = &tile.sums[(std::size_t(r) * std::size_t(tile.bw) + std::size_t(c)) * 4];
      if (src[3] == 0 && src[0] == 0 && src[1] == 0 && src[2] == 0) continue;
      std::int64_t* dst = &fixed_[index(tile.bx0 + c, tile.brow0 + r) * 4];
      for (int k = 0; k < 4; ++k) std::atomic_ref<std::int64_t>(dst[k]).fetch_add(src[k], std::memory_order_relaxed);
    }
  std::fill(tile.sums.begin(), tile.sums.end(), 0);
}

Image Film::resolve() const {
  Image image(width_, height_);
  for (int row = 0; row < height_; ++row)
    for (int x = 0; x < width_; ++x) {
      const std::size_t i = index(x, row) * 4;
      Vec3 sum;
      double w;
      if (local_) {
        const auto load = [&](int k) {
          return std::atomic_ref<double>(const_cast<double&>(local_sums_[i + std::size_t(k)])).load(std::memory_order_relaxed);
        };
        sum = {load(0), load(1), load(2)};
        w = load(3);
      } else {
        const auto load = [&](int k) {
          return double(std::atomic_ref<std::int64_t>(const_cast<std::int64_t&>(fixed_[i + std::size_t(k)]))
                            .load(std::memory_order_relaxed)) /
                 kFixedScale;
        };
        sum = {load(0), load(1), load(2)};
        w = load(3);
      }
      if (w != 0) {  // as pbrt: Mitchell's negative lobes can make a sparse pixel's sum negative
        const Vec3 c = sum / w;
        image.at(x, row) = Rgb{float(c.x), float(c.y), float(c.z)};
      }
    }
  return image;
}

}  // namespace strahl
