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

FilmLayout::FilmLayout(int width, int height, const Filter& filter, bool pixel_stats)
    : width_(width),
      height_(height),
      filter_(filter),
      local_(filter_is_pixel_local(filter)),
      stats_(pixel_stats),
      margin_(int(std::ceil(filter.radius)) + 1) {}

void FilmLayout::prepare(TileWork& t) const {
  const std::size_t n = t.rect.pixels();
  t.taken.assign(n, 0);
  t.counters = {};
  // Sums and statistics carried in (a decoded request) are kept; missing ones start at zero.
  if (stats_ && t.stats.size() != n) t.stats.assign(n, PixelStats{});
  if (local_) {
    if (t.local.size() != n * 4) t.local.assign(n * 4, 0.0);
    return;
  }
  t.bx0 = std::max(0, t.rect.x0 - margin_);
  t.brow0 = std::max(0, t.rect.row0 - margin_);
  t.bw = std::min(width_, t.rect.x1 + margin_) - t.bx0;
  t.bh = std::min(height_, t.rect.row1 + margin_) - t.brow0;
  t.fixed.assign(std::size_t(t.bw) * std::size_t(t.bh) * 4, 0);
}

void FilmLayout::add_sample(TileWork& tile, int x, int row, const CameraSample& cs, const Vec3& L) const {
  const std::size_t own = tile.rect.index(x, row);
  if (stats_) {
    PixelStats& st = tile.stats[own];
    const double lum = luminance(L);
    st.sum += lum;
    st.sum_sq += lum * lum;
    ++st.n;
  }

  if (local_) {
    double* p = &tile.local[own * 4];
    p[0] += L.x;
    p[1] += L.y;
    p[2] += L.z;
    p[3] += 1.0;
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
          &tile.fixed[(std::size_t(prow - tile.brow0) * std::size_t(tile.bw) + std::size_t(px - tile.bx0)) * 4];
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

Film::Film(int width, int height, const Filter& filter, bool pixel_stats)
    : Film(FilmLayout(width, height, filter, pixel_stats)) {}

Film::Film(const FilmLayout& layout) : layout_(layout) {
  const std::size_t pixels = std::size_t(width()) * std::size_t(height());
  if (layout_.keeps_stats()) stats_.assign(pixels, PixelStats{});
  if (layout_.pixel_local())
    local_sums_.assign(pixels * 4, 0.0);
  else
    fixed_.assign(pixels * 4, 0);
}

void Film::begin_tile(TileWork& t) const {
  layout_.prepare(t);
  const TileRect& r = t.rect;
  for (int row = r.row0; row < r.row1; ++row)
    for (int x = r.x0; x < r.x1; ++x) {
      const std::size_t own = r.index(x, row), p = index(x, row);
      if (!stats_.empty()) t.stats[own] = stats_[p];
      if (pixel_local())
        for (int c = 0; c < 4; ++c) t.local[own * 4 + std::size_t(c)] = local_sums_[p * 4 + std::size_t(c)];
    }
}

void Film::merge(const TileWork& t) {
  const TileRect& r = t.rect;
  for (int row = r.row0; row < r.row1; ++row)
    for (int x = r.x0; x < r.x1; ++x) {
      const std::size_t own = r.index(x, row), p = index(x, row);
      if (!stats_.empty()) stats_[p] = t.stats[own];
      // Only this tile writes the pixel; atomic stores let resolve() read meanwhile.
      if (pixel_local())
        for (int c = 0; c < 4; ++c)
          std::atomic_ref<double>(local_sums_[p * 4 + std::size_t(c)])
              .store(t.local[own * 4 + std::size_t(c)], std::memory_order_relaxed);
    }
  if (pixel_local()) return;
  for (int r2 = 0; r2 < t.bh; ++r2)
    for (int c = 0; c < t.bw; ++c) {
      const std::int64_t* src = &t.fixed[(std::size_t(r2) * std::size_t(t.bw) + std::size_t(c)) * 4];
      if (src[3] == 0 && src[0] == 0 && src[1] == 0 && src[2] == 0) continue;
      std::int64_t* dst = &fixed_[index(t.bx0 + c, t.brow0 + r2) * 4];
      for (int k = 0; k < 4; ++k) std::atomic_ref<std::int64_t>(dst[k]).fetch_add(src[k], std::memory_order_relaxed);
    }
}

std::array<double, 4> Film::sums(int x, int row) const {
  std::array<double, 4> s{};
  const std::size_t i = index(x, row) * 4;
  for (std::size_t k = 0; k < 4; ++k)
    s[k] = pixel_local() ? local_sums_[i + k] : double(fixed_[i + k]) / kFixedScale;
  return s;
}

Image Film::resolve() const {
  Image image(width(), height());
  for (int row = 0; row < height(); ++row)
    for (int x = 0; x < width(); ++x) {
      const std::size_t i = index(x, row) * 4;
      Vec3 sum;
      double w;
      if (pixel_local()) {
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
