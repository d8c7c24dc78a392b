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

// STRAHL_PORTABLE_KERNELS: the scalar path (what the GPU runs) on an AVX2 host too
// (tests/portable checks the two give the same film sums, bit for bit).
#if !defined(__CUDACC__) && defined(__AVX2__) && !defined(STRAHL_PORTABLE_KERNELS)
#include <immintrin.h>
#define STRAHL_FILM_AVX 1
#endif

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

// film_to_fixed(v[k]) into out[k], k < 4: with AVX2 in one vector, the same values bit for bit.
// llround's halves away from zero are x + copysign(0.49999999999999994, x) truncated (as GCC
// inlines llround; exact for |x| < 2^52, and every clamped value times the scale is below 2^49);
// the truncation is AVX-512's conversion itself, or with AVX2 a rounding and 1.5·2^52 added, which
// leaves the integer in the low bits. A NaN gives INT64_MIN, as the scalar conversion does on x86.
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void film_to_fixed4(const double* v, std::int64_t* out) {
#if defined(STRAHL_FILM_AVX)
  __m256d x = _mm256_loadu_pd(v);
  x = _mm256_max_pd(_mm256_set1_pd(-kFilmFixedLimit), x);  // a NaN passes: max and min return
  x = _mm256_min_pd(_mm256_set1_pd(kFilmFixedLimit), x);   // their second operand then
  x = _mm256_mul_pd(x, _mm256_set1_pd(kFilmFixedScale));
  const __m256d sign = _mm256_and_pd(x, _mm256_set1_pd(-0.0));
  x = _mm256_add_pd(x, _mm256_or_pd(sign, _mm256_set1_pd(0.49999999999999994)));
#if defined(__AVX512DQ__) && defined(__AVX512VL__)
  const __m256i q = _mm256_cvttpd_epi64(x);
#else
  const __m256d t = _mm256_round_pd(x, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC);
  const __m256d magic = _mm256_set1_pd(6755399441055744.0);  // 1.5 · 2^52
  __m256i q = _mm256_sub_epi64(_mm256_castpd_si256(_mm256_add_pd(t, magic)), _mm256_castpd_si256(magic));
  q = _mm256_blendv_epi8(q, _mm256_set1_epi64x(INT64_MIN), _mm256_castpd_si256(_mm256_cmp_pd(x, x, _CMP_UNORD_Q)));
#endif
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), q);
#else
  for (int k = 0; k < 4; ++k) out[k] = film_to_fixed(v[k]);
#endif
}

// Wide filter: the sample of pixel (x, row) at film position (cs.film_x, cs.film_y) into every
// pixel whose centre lies within the filter's support, as fixed-point r, g, b, weight in the
// buffer [bx0, bx0 + bw) × [brow0, …) (`fixed`, four int64 per pixel); add(p, v) adds v to *p.
// A contribution's weight is quantised first and its values weighted by the quantised weight: a
// flat image then resolves to its value up to the rounding of each product. A row's weights are
// quantised four at a time, a contribution's four values together (film_to_fixed4).
template <class Add>
STRAHL_HOST_DEVICE inline void film_add_wide(const FilmParams& f, int x, int row, const CameraSample& cs, const Vec3& L,
                                             std::int64_t* fixed, int bx0, int brow0, int bw, Add&& add) {
  // Pixels (px, py) (py counted from the bottom) whose centre lies within the filter's support.
  const Real r = f.filter.radius;
  const int y = f.height - 1 - row;
  Real wx[16], wy[16];  // 2·margin + 1 ≤ 11 (radius ≤ 4), rounded up to a multiple of 4
  const auto imax = [](int a, int b) { return a > b ? a : b; };
  const auto imin = [](int a, int b) { return a < b ? a : b; };
  const int px0 = imax(imax(0, x - f.margin), int(std::floor(cs.film_x - Real(0.5) - r)));
  const int px1 = imin(imin(f.width - 1, x + f.margin), int(std::ceil(cs.film_x - Real(0.5) + r)));
  const int py0 = imax(imax(0, y - f.margin), int(std::floor(cs.film_y - Real(0.5) - r)));
  const int py1 = imin(imin(f.height - 1, y + f.margin), int(std::ceil(cs.film_y - Real(0.5) + r)));
  const int nx = px1 - px0 + 1, nx4 = (nx + 3) & ~3;
  filter_weights_1d(f.filter, f.filter_edge, cs.film_x, px0, nx, wx);
  filter_weights_1d(f.filter, f.filter_edge, cs.film_y, py0, py1 - py0 + 1, wy);
  for (int i = nx; i < nx4; ++i) wx[i] = 0;
  for (int py = py0; py <= py1; ++py) {
    const Real wr = wy[py - py0];
    if (wr == 0) continue;
    Real w[16];
    std::int64_t qw[16];
    for (int i = 0; i < nx4; ++i) w[i] = wx[i] * wr;
    for (int i = 0; i < nx4; i += 4) film_to_fixed4(w + i, qw + i);
    const int prow = f.height - 1 - py;
    std::int64_t* p = fixed + (std::size_t(prow - brow0) * std::size_t(bw) + std::size_t(px0 - bx0)) * 4;
    for (int i = 0; i < nx; ++i, p += 4) {
      if (w[i] == 0) continue;
      const double fw = double(qw[i]) / kFilmFixedScale;
      const double v[4] = {fw * L.x, fw * L.y, fw * L.z, w[i]};  // film_to_fixed(w[i]) is qw[i] again
      std::int64_t q[4];
      film_to_fixed4(v, q);
      for (int k = 0; k < 4; ++k) add(p + k, q[k]);
    }
  }
}

}  // namespace strahl
