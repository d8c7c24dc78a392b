#include "strahl/render/adaptive.h"

#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace strahl {

namespace {

constexpr std::size_t kBandRows = 16;  // rows per unit of parallel work

// f(first row, end row) for bands of kBandRows rows, on all threads; `band` numbers them.
template <typename F>
void for_each_band(std::size_t h, F&& f) {
  const std::size_t bands = (h + kBandRows - 1) / kBandRows;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bands), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t band = r.begin(); band < r.end(); ++band)
      f(band, band * kBandRows, std::min(h, (band + 1) * kBandRows));
  });
}

}  // namespace

std::uint64_t AdaptivePlanner::plan_every_pixel(const Film& film, std::span<const std::uint32_t> counts,
                                                std::uint32_t max_spp, double threshold, std::vector<std::uint32_t>& add,
                                                std::uint64_t* headroom) {
  // (Each band reads the sizes and the threshold into locals of its own: its byte stores could
  // alias the captured ones, and GCC would then reload them per pixel and vectorise no row loop.)
  const std::size_t width = std::size_t(film.width()), height = std::size_t(film.height());
  const ZeroedArray<PixelStats>& stats = film.pixel_stats();
  // Errors, and over_ along each row's neighbours (near_), band by band; each band divides out
  // the means of its rows and the rows next to it.
  for_each_band(height, [&](std::size_t, std::size_t row0, std::size_t row1) {
    const std::size_t w = width, h = height;
    const double limit = threshold;
    const std::size_t m0 = row0 > 0 ? row0 - 1 : 0, m1 = std::min(h, row1 + 1);
    // (Every entry is written before it is read: no zeroing first.)
    const std::unique_ptr<double[]> means(new double[(m1 - m0) * w]), contrast_row(new double[w]);
    double* const contrasts = contrast_row.get();
    for (std::size_t p = m0 * w; p < m1 * w; ++p)
      means[p - m0 * w] = stats[p].n > 0 ? stats[p].sum / stats[p].n : std::numeric_limits<double>::quiet_NaN();
    for (std::size_t p = row0 * w; p < row1 * w; ++p) seen_[p] = counts[p];
    const auto mean_row = [&](std::size_t row) { return &means[(row - m0) * w]; };
    for (std::size_t row = row0; row < row1; ++row) {
      const double* above = mean_row(row > 0 ? row - 1 : row);
      const double* here = mean_row(row);
      const double* below = mean_row(row + 1 < h ? row + 1 : row);
      // contrast_error's largest difference to a neighbour, for every pixel of the row.
      const auto contrast = [&](std::size_t x, std::size_t l, std::size_t r) {
        const double m = here[x];
        double e = 0;
        e = std::max(e, std::abs(m - above[l])), e = std::max(e, std::abs(m - above[x])), e = std::max(e, std::abs(m - above[r]));
        e = std::max(e, std::abs(m - here[l])), e = std::max(e, std::abs(m - here[r]));
        e = std::max(e, std::abs(m - below[l])), e = std::max(e, std::abs(m - below[x])), e = std::max(e, std::abs(m - below[r]));
        return e;
      };
      contrasts[0] = contrast(0, 0, w > 1 ? 1 : 0);
      for (std::size_t x = 1; x + 1 < w; ++x) contrasts[x] = contrast(x, x - 1, x + 1);
      if (w > 1) contrasts[w - 1] = contrast(w - 1, w - 2, w - 1);
      std::uint8_t* o = &over_[row * w];
      // pixel_error(): the contrast for every pixel side by side, then the pixels with other
      // than one sample (their relative error).
      for (std::size_t x = 0; x < w; ++x) {
        const double mean = here[x] < 0.01 ? 0.01 : here[x];  // std::max(here[x], 0.01)
        o[x] = std::uint8_t(contrasts[x] / mean > limit ? 1 : 0);
      }
      for (std::size_t x = 0; x < w; ++x)
        if (stats[row * w + x].n != 1) o[x] = relative_error(stats[row * w + x]) > limit;
      // more(): a pixel refines when its 3×3 neighbourhood has one over the threshold — the largest
      // over_ along each row's neighbours here, down the columns below.
      std::uint8_t* n = &near_[row * w];
      n[0] = o[0] | o[w > 1 ? 1 : 0];
      for (std::size_t x = 1; x + 1 < w; ++x) n[x] = o[x - 1] | o[x] | o[x + 1];
      if (w > 1) n[w - 1] = o[w - 2] | o[w - 1];
    }
  });
  bands_.resize((height + kBandRows - 1) / kBandRows);
  for_each_band(height, [&](std::size_t band, std::size_t row0, std::size_t row1) {
    const std::size_t w = width, h = height;
    Band& b = bands_[band];
    b.planned.clear();
    b.total = b.room = 0;
    for (std::size_t row = row0; row < row1; ++row) {
      const std::uint8_t* above = &near_[(row > 0 ? row - 1 : row) * w];
      const std::uint8_t* here = &near_[row * w];
      const std::uint8_t* below = &near_[(row + 1 < h ? row + 1 : row) * w];
      // The row's counts side by side, then the pixels that take samples listed.
      const std::uint32_t* const c = &counts[row * w];
      std::uint32_t* const a = &add[row * w];
      std::uint32_t any = 0;
      for (std::size_t x = 0; x < w; ++x) {
        a[x] = doubled((above[x] | here[x] | below[x]) != 0, c[x], max_spp);
        any |= a[x];
      }
      if (any == 0) continue;
      for (std::size_t x = 0; x < w; ++x) {
        if (a[x] == 0) continue;
        b.planned.push_back(std::uint32_t(row * w + x));
        b.total += a[x];
        b.room += max_spp - c[x];
      }
    }
  });
  std::uint64_t total = 0, room = 0;
  planned_.clear();
  for (const Band& b : bands_) {
    planned_.insert(planned_.end(), b.planned.begin(), b.planned.end());
    total += b.total;
    room += b.room;
  }
  if (headroom != nullptr) *headroom = room;
  return total;
}

}  // namespace strahl
