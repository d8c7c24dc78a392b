#include "strahl/render/film.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace strahl {

namespace {

constexpr double kFixedScale = kFilmFixedScale;

}  // namespace

FilmLayout::FilmLayout(int width, int height, const Filter& filter, bool pixel_stats)
    : width_(width),
      height_(height),
      filter_(filter),
      local_(filter_is_pixel_local(filter)),
      stats_(pixel_stats),
      margin_(int(std::ceil(filter.radius)) + 1),
      filter_edge_(filter_edge(filter)) {}

FilmParams FilmLayout::params() const {
  FilmParams p;
  p.width = width_;
  p.height = height_;
  p.filter = filter_;
  p.local = local_;
  p.stats = stats_;
  p.margin = margin_;
  p.filter_edge = filter_edge_;
  return p;
}

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

void FilmLayout::add_wide(TileWork& tile, int x, int row, const CameraSample& cs, const Vec3& L) const {
  film_add_wide(params(), x, row, cs, L, tile.fixed.data(), tile.bx0, tile.brow0, tile.bw,
                [](std::int64_t* p, std::int64_t v) { *p += v; });
}

Film::Film(int width, int height, const Filter& filter, bool pixel_stats)
    : Film(FilmLayout(width, height, filter, pixel_stats)) {}

Film::Film(const FilmLayout& layout) : layout_(layout) {
  const std::size_t pixels = std::size_t(width()) * std::size_t(height());
  if (layout_.keeps_stats()) stats_ = ZeroedArray<PixelStats>(pixels);
  if (layout_.pixel_local())
    local_sums_ = ZeroedArray<double>(pixels * 4);
  else
    fixed_ = ZeroedArray<std::int64_t>(pixels * 4);
}

void Film::begin_tile(TileWork& t) const {
  layout_.prepare(t);
  const TileRect& r = t.rect;
  const std::size_t tw = std::size_t(r.width());
  const bool counted = t.count.size() == r.pixels(), known_first = t.first.size() == r.pixels();
  for (int row = r.row0; row < r.row1; ++row) {
    const std::size_t own = std::size_t(row - r.row0) * tw, p = index(r.x0, row);
    // A row whose pixels take no samples (most rows of a sparse pass's tile): nothing to carry in.
    if (counted && !any_counted(&t.count[own], tw)) continue;
    // A row of pixels without samples so far (the first pass) starts from zero: the film's state of
    // them is zero, and not reading it leaves its pages untouched until the tile is merged.
    if (known_first && !any_counted(&t.first[own], tw)) {
      if (!stats_.empty()) std::fill_n(&t.stats[own], tw, PixelStats{});
      if (pixel_local()) std::fill_n(&t.local[own * 4], tw * 4, 0.0);
      continue;
    }
    // Only the pixels that take samples (a sparse adaptive pass: a few of the tile's); the state of
    // the others is not read (render_tile) nor taken back (merge).
    if (counted && !all_counted(&t.count[own], tw)) {
      for (std::size_t k = 0; k < tw; ++k) {
        if (t.count[own + k] == 0) continue;
        if (!stats_.empty()) t.stats[own + k] = stats_[p + k];
        if (pixel_local()) std::copy_n(&local_sums_[(p + k) * 4], 4, &t.local[(own + k) * 4]);
      }
      continue;
    }
    if (!stats_.empty()) std::copy_n(&stats_[p], tw, &t.stats[own]);
    // Only this tile writes these pixels, and not before it is merged: plain reads.
    if (pixel_local()) std::copy_n(&local_sums_[p * 4], tw * 4, &t.local[own * 4]);
  }
}

void Film::merge(const TileWork& t) {
  const TileRect& r = t.rect;
  const std::size_t tw = std::size_t(r.width());
  for (int row = r.row0; row < r.row1; ++row) {
    const std::size_t own = std::size_t(row - r.row0) * tw, p = index(r.x0, row);
    // The pixels that took samples (all of a row, or the few of a sparse pass; often none).
    if (!any_counted(&t.taken[own], tw)) continue;
    const bool whole = all_counted(&t.taken[own], tw);
    for (std::size_t k = 0; k < tw; ++k) {
      if (!whole && t.taken[own + k] == 0) continue;
      if (!stats_.empty()) stats_[p + k] = t.stats[own + k];
      if (!pixel_local()) continue;
      // Only this tile writes the pixels; atomic stores let resolve() read meanwhile.
      const double* src = &t.local[(own + k) * 4];
      double* dst = &local_sums_[(p + k) * 4];
      for (std::size_t c = 0; c < 4; ++c) std::atomic_ref<double>(dst[c]).store(src[c], std::memory_order_relaxed);
    }
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
  // Rows in parallel (the image's fresh pages are first written here, by whichever thread).
  tbb::parallel_for(tbb::blocked_range<int>(0, height(), 16), [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row < rows.end(); ++row)
      for (int x = 0; x < width(); ++x) {
        const std::size_t i = index(x, row) * 4;
        Vec3 sum;
        double w;
        if (pixel_local()) {
          const auto load = [&](int k) {
            return std::atomic_ref<double>(const_cast<double&>(local_sums_[i + std::size_t(k)]))
                .load(std::memory_order_relaxed);
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
  });
  return image;
}

}  // namespace strahl
