#pragma once
// The film's per-sample arithmetic as kernel code (STRAHL_HOST_DEVICE): how one camera sample's
// radiance lands in a tile's buffers (render/tile.h). FilmLayout::add_sample (render/film.h) on
// the CPU and the CUDA kernel (cuda/) run these same functions, so a pixel's sums are the same
// additions on either device: pixel-local filters add in double in sample order; wide filters add
// 64-bit fixed-point contributions, through `add` (a plain += on the CPU, an atomic add on the
// GPU: integer additions commute, so the order threads add them in does not change the result).

#include <cmath>
#include <cstdint>

#include "strahl/camera/camera_sample.h"
#include "strahl/math/vec3.h"
#include "strahl/render/tile.h"
#include "strahl/sampling/filter.h"

namespace strahl {

inline constexpr double kFilmFixedScale = 268435456.0;  // 2^28 units per 1
// Larger contributions are clamped so that sums of many stay far from int64 overflow.
inline constexpr double kFilmFixedLimit = 1e6;

STRAHL_HOST_DEVICE inline double film_luminance(const Vec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

STRAHL_HOST_DEVICE inline std::int64_t film_to_fixed(double v) {
  // std::clamp's comparisons (a NaN passes through, as before).
  v = v < -kFilmFixedLimit ? -kFilmFixedLimit : (kFilmFixedLimit < v ? kFilmFixedLimit : v);
#if defined(__CUDA_ARCH__)
  return ::llround(v * kFilmFixedScale);
#else
  return std::llround(v * kFilmFixedScale);
#endif
}

// What a sample needs of the film: plain data, copied to the device.
struct FilmParams {
  int width = 0, height = 0;
  Filter filter;
  bool local = true;  // pixel-local filter (box of radius 0.5)
  bool stats = false; // keep per-pixel luminance statistics
  int margin = 1;     // pixels a sample can reach beyond its own
  Real filter_edge = 0;  // filter_edge(filter), computed once
};

// Adaptive sampling's statistics of the pixel's own samples.
STRAHL_HOST_DEVICE inline void film_add_stats(PixelStats& st, const Vec3& L) {
  const double lum = film_luminance(L);
  st.sum += lum;
  st.sum_sq += lum * lum;
  ++st.n;
}

// Pixel-local filter: Σ L (r, g, b) and Σ 1 of the pixel, `p` its four sums.
STRAHL_HOST_DEVICE inline void film_add_local(double* p, const Vec3& L) {
  p[0] += L.x;
  p[1] += L.y;
  p[2] += L.z;
  p[3] += 1.0;
}

// Wide filter: the sample of pixel (x, row) at film position (cs.film_x, cs.film_y) into every
// pixel whose centre lies within the filter's support, as fixed-point r, g, b, weight in the
// buffer [bx0, bx0 + bw) × [brow0, …) (`fixed`, four int64 per pixel); add(p, v) adds v to *p.
template <class Add>
STRAHL_HOST_DEVICE inline void film_add_wide(const FilmParams& f, int x, int row, const CameraSample& cs, const Vec3& L,
                                             std::int64_t* fixed, int bx0, int brow0, int bw, Add&& add) {
  // Pixels (px, py) (py counted from the bottom) whose centre lies within the filter's support.
  const Real r = f.filter.radius;
  const int y = f.height - 1 - row;
  Real wx[16], wy[16];
  const auto imax = [](int a, int b) { return a > b ? a : b; };
  const auto imin = [](int a, int b) { return a < b ? a : b; };
  const int px0 = imax(imax(0, x - f.margin), int(std::floor(cs.film_x - Real(0.5) - r)));
  const int px1 = imin(imin(f.width - 1, x + f.margin), int(std::ceil(cs.film_x - Real(0.5) + r)));
  const int py0 = imax(imax(0, y - f.margin), int(std::floor(cs.film_y - Real(0.5) - r)));
  const int py1 = imin(imin(f.height - 1, y + f.margin), int(std::ceil(cs.film_y - Real(0.5) + r)));
  filter_weights_1d(f.filter, f.filter_edge, cs.film_x, px0, px1 - px0 + 1, wx);
  filter_weights_1d(f.filter, f.filter_edge, cs.film_y, py0, py1 - py0 + 1, wy);
  for (int py = py0; py <= py1; ++py) {
    if (wy[py - py0] == 0) continue;
    const int prow = f.height - 1 - py;
    for (int px = px0; px <= px1; ++px) {
      const Real w = wx[px - px0] * wy[py - py0];
      if (w == 0) continue;
      std::int64_t* p = fixed + (std::size_t(prow - brow0) * std::size_t(bw) + std::size_t(px - bx0)) * 4;
      // The weight quantised first and the values weighted by the quantised weight: a flat
      // image then resolves to its value up to the rounding of each product.
      const std::int64_t qw = film_to_fixed(w);
      const double fw = double(qw) / kFilmFixedScale;
      add(p + 0, film_to_fixed(fw * L.x));
      add(p + 1, film_to_fixed(fw * L.y));
      add(p + 2, film_to_fixed(fw * L.z));
      add(p + 3, qw);
    }
  }
}

}  // namespace strahl
