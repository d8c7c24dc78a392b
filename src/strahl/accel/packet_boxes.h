#pragma once
// The boxes of the packet traversal (wide_bvh_packet.h): per lane the figures of wide_bvh.h's
// ray_boxes() in float, the packet's frustum over them, and a node's children tested against the
// lanes (AVX-512, AVX2 or a scalar loop, the same figures).

#include <cstdint>

#include "strahl/accel/packet_simd.h"
#include "strahl/accel/wide_bvh.h"

STRAHL_PACKET_WARNINGS_OFF

namespace strahl::wide_bvh_packet_detail {

// Per lane, structure of arrays: the box-test figures of ray_boxes() and the interval, in float.
template <int N>
struct alignas(64) PacketBoxes {
  float inv[3][N];
  float near_offset[3][N];
  float far_offset[3][N];
  float t_min[N];
  float t_max[N];  // round_up(the lane's t_max); lowered as hits are found
  // Bit a set: every active lane's direction is negative along axis a (signbit); −1: the lanes'
  // signs differ along some axis. Where they agree the near plane of a box is the same for every
  // lane (lo, or hi where negative) and the SIMD tests skip the per-lane min/max.
  int signs = -1;
  // The packet's frustum (frustum_children()): over the active lanes, per axis the smallest and
  // largest inv and the smallest near / largest far offset; the smallest t_min and the largest
  // t_max (lowered as the lanes' t_max are).
  float f_inv_lo[3] = {0, 0, 0}, f_inv_hi[3] = {0, 0, 0};
  float f_near[3] = {0, 0, 0}, f_far[3] = {0, 0, 0};
  float f_t_min = 0, f_t_max = 0;
};

struct PacketStackEntry {
  std::uint32_t child, count, lanes;
  float t_near;  // the smallest entry distance among `lanes`
};

template <int N>
STRAHL_HOST_DEVICE inline void set_lane(PacketBoxes<N>& p, int i, const WideBvhView& bvh, const Ray& ray, Real t_min,
                                        Real t_max) {
  const wide_bvh_detail::RayBoxes rb = wide_bvh_detail::ray_boxes(bvh, ray);
  for (int a = 0; a < 3; ++a) {
    p.inv[a][i] = rb.inv[a];
    p.near_offset[a][i] = rb.near_offset[a];
    p.far_offset[a][i] = rb.far_offset[a];
  }
  p.t_min[i] = wide_bvh_detail::round_down(t_min);
  p.t_max[i] = wide_bvh_detail::round_up(t_max);
}

// An inactive lane: meets no box (t_min = +∞ > t_max = −∞) and has finite figures.
template <int N>
STRAHL_HOST_DEVICE inline void clear_lane(PacketBoxes<N>& p, int i) {
  for (int a = 0; a < 3; ++a) p.inv[a][i] = p.near_offset[a][i] = p.far_offset[a][i] = 0;
  p.t_min[i] = std::numeric_limits<float>::infinity();
  p.t_max[i] = -std::numeric_limits<float>::infinity();
}

#if defined(STRAHL_PACKET_AVX2)
// round_down (kUp false) / round_up (true) of four doubles: the nearest float, stepped one ulp
// down (up) where it lies above (below) the double (from ±0 to ∓ the smallest subnormal, from ±∞
// to ±FLT_MAX).
template <bool kUp>
STRAHL_FORCE_INLINE __m128 round_out4(__m256d x) {
  const __m128 f = _mm256_cvtpd_ps(x);
  const __m256d back = _mm256_cvtps_pd(f);
  const __m256d beyond = kUp ? _mm256_cmp_pd(back, x, _CMP_LT_OQ) : _mm256_cmp_pd(back, x, _CMP_GT_OQ);
  const __m128i off = _mm256_castsi256_si128(
      _mm256_permutevar8x32_epi32(_mm256_castpd_si256(beyond), _mm256_setr_epi32(0, 2, 4, 6, 0, 0, 0, 0)));
  const __m128i bits = _mm_castps_si128(f);
  // Away from zero on the side of the step (bits + 1), towards it on the other (bits − 1).
  const __m128 away = kUp ? _mm_cmpgt_ps(f, _mm_setzero_ps()) : _mm_cmplt_ps(f, _mm_setzero_ps());
  __m128i step = _mm_blendv_epi8(_mm_sub_epi32(bits, _mm_set1_epi32(1)), _mm_add_epi32(bits, _mm_set1_epi32(1)),
                                 _mm_castps_si128(away));
  step = _mm_blendv_epi8(step, _mm_set1_epi32(kUp ? 1 : std::int32_t(0x80000001u)),
                         _mm_castps_si128(_mm_cmpeq_ps(f, _mm_setzero_ps())));
  return _mm_castsi128_ps(_mm_blendv_epi8(bits, step, off));
}
#endif

// The frustum of the lanes in `active` (their figures set): see frustum_children().
#if defined(STRAHL_PACKET_AVX2)
// Lane masks and horizontal minima / maxima of eight floats.
STRAHL_FORCE_INLINE __m256 lane_mask8(unsigned lanes8) {
  const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  return _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(lanes8)), bit), bit));
}
STRAHL_FORCE_INLINE float min8(__m256 v) {
  __m128 m = _mm_min_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  m = _mm_min_ps(m, _mm_movehl_ps(m, m));
  m = _mm_min_ss(m, _mm_shuffle_ps(m, m, 1));
  return _mm_cvtss_f32(m);
}
STRAHL_FORCE_INLINE float max8(__m256 v) {
  __m128 m = _mm_max_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  m = _mm_max_ps(m, _mm_movehl_ps(m, m));
  m = _mm_max_ss(m, _mm_shuffle_ps(m, m, 1));
  return _mm_cvtss_f32(m);
}
#endif

template <int N>
STRAHL_HOST_DEVICE inline void set_frustum(PacketBoxes<N>& p, std::uint32_t active) {
  const float inf = std::numeric_limits<float>::infinity();
#if defined(STRAHL_PACKET_AVX2)
  if constexpr (N % 8 == 0) {
    const __m256 pinf = _mm256_set1_ps(inf), ninf = _mm256_set1_ps(-inf);
    __m256 il[3], ih[3], ne[3], fa[3], tn = pinf, tf = ninf;
    for (int a = 0; a < 3; ++a) il[a] = ne[a] = pinf, ih[a] = fa[a] = ninf;
    for (int h = 0; h < N; h += 8) {
      const __m256 on = lane_mask8((active >> h) & 0xffu);
      for (int a = 0; a < 3; ++a) {
        const __m256 inv = _mm256_load_ps(p.inv[a] + h);
        il[a] = _mm256_min_ps(il[a], _mm256_blendv_ps(pinf, inv, on));
        ih[a] = _mm256_max_ps(ih[a], _mm256_blendv_ps(ninf, inv, on));
        ne[a] = _mm256_min_ps(ne[a], _mm256_blendv_ps(pinf, _mm256_load_ps(p.near_offset[a] + h), on));
        fa[a] = _mm256_max_ps(fa[a], _mm256_blendv_ps(ninf, _mm256_load_ps(p.far_offset[a] + h), on));
      }
      tn = _mm256_min_ps(tn, _mm256_blendv_ps(pinf, _mm256_load_ps(p.t_min + h), on));
      tf = _mm256_max_ps(tf, _mm256_blendv_ps(ninf, _mm256_load_ps(p.t_max + h), on));
    }
    for (int a = 0; a < 3; ++a) {
      p.f_inv_lo[a] = min8(il[a]);
      p.f_inv_hi[a] = max8(ih[a]);
      p.f_near[a] = min8(ne[a]);
      p.f_far[a] = max8(fa[a]);
    }
    p.f_t_min = min8(tn);
    p.f_t_max = max8(tf);
    return;
  }
#endif
  for (int a = 0; a < 3; ++a) {
    p.f_inv_lo[a] = p.f_near[a] = inf;
    p.f_inv_hi[a] = p.f_far[a] = -inf;
  }
  p.f_t_min = inf;
  p.f_t_max = -inf;
  for (int i = 0; i < N; ++i) {
    if (((active >> i) & 1u) == 0) continue;
    for (int a = 0; a < 3; ++a) {
      p.f_inv_lo[a] = p.inv[a][i] < p.f_inv_lo[a] ? p.inv[a][i] : p.f_inv_lo[a];
      p.f_inv_hi[a] = p.inv[a][i] > p.f_inv_hi[a] ? p.inv[a][i] : p.f_inv_hi[a];
      p.f_near[a] = p.near_offset[a][i] < p.f_near[a] ? p.near_offset[a][i] : p.f_near[a];
      p.f_far[a] = p.far_offset[a][i] > p.f_far[a] ? p.far_offset[a][i] : p.f_far[a];
    }
    p.f_t_min = p.t_min[i] < p.f_t_min ? p.t_min[i] : p.f_t_min;
    p.f_t_max = p.t_max[i] > p.f_t_max ? p.t_max[i] : p.f_t_max;
  }
}

// The largest t_max among the lanes in `active`, after some of them were lowered.
template <int N>
STRAHL_HOST_DEVICE inline void lower_frustum(PacketBoxes<N>& p, std::uint32_t active) {
#if defined(STRAHL_PACKET_AVX2)
  if constexpr (N % 8 == 0) {
    const __m256 ninf = _mm256_set1_ps(-std::numeric_limits<float>::infinity());
    __m256 tf = ninf;
    for (int h = 0; h < N; h += 8)
      tf = _mm256_max_ps(tf, _mm256_blendv_ps(ninf, _mm256_load_ps(p.t_max + h), lane_mask8((active >> h) & 0xffu)));
    p.f_t_max = max8(tf);
    return;
  }
#endif
  float m = -std::numeric_limits<float>::infinity();
  for (int i = 0; i < N; ++i)
    if (((active >> i) & 1u) && p.t_max[i] > m) m = p.t_max[i];
  p.f_t_max = m;
}

// Bit a set where every active lane's direction is negative along axis a (signbit); −1 when the
// active lanes' signs differ on some axis (PacketBoxes::signs).
template <int N>
STRAHL_HOST_DEVICE inline int shared_signs(std::uint32_t active, const Ray* rays) {
  int any_sign = 0, all_sign = 7;
  for (int i = 0; i < N; ++i) {
    if (((active >> i) & 1u) == 0) continue;
    const Vec3& d = rays[i].direction;
    const int sign = (std::signbit(d.x) ? 1 : 0) | (std::signbit(d.y) ? 2 : 0) | (std::signbit(d.z) ? 4 : 0);
    any_sign |= sign;
    all_sign &= sign;
  }
  return any_sign == all_sign ? all_sign : -1;
}

// Every lane of the packet: set_lane() for the active ones, clear_lane() for the others. With
// AVX-512 ray_boxes()'s double arithmetic runs eight lanes at once, the same IEEE operations in
// the same order (so the same figures as set_lane()).
template <int N>
STRAHL_HOST_DEVICE inline void set_lanes(PacketBoxes<N>& p, std::uint32_t active, const WideBvhView& bvh,
                                         const Ray* rays, const Real* t_min, const Real* t_max) {
#if defined(STRAHL_PACKET_AVX512)
  p.signs = shared_signs<N>(active, rays);
  alignas(64) double o[3][N], d[3][N];
  for (int i = 0; i < N; ++i) {
    const bool on = (active >> i) & 1u;
    o[0][i] = on ? rays[i].origin.x : 0;
    o[1][i] = on ? rays[i].origin.y : 0;
    o[2][i] = on ? rays[i].origin.z : 0;
    d[0][i] = on ? rays[i].direction.x : 1;
    d[1][i] = on ? rays[i].direction.y : 1;
    d[2][i] = on ? rays[i].direction.z : 1;
  }
  const __m512d one = _mm512_set1_pd(1.0), scale = _mm512_set1_pd(0x1p-21);
  const __m256 inf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
  const __m256 sign = _mm256_set1_ps(-0.0f);
  const auto finite = [&](__m256 x) { return _mm256_cmp_ps(_mm256_andnot_ps(sign, x), inf, _CMP_LT_OQ); };
  for (int a = 0; a < 3; ++a) {
    const __m512d extent = _mm512_set1_pd(Real(bvh.extent[a]));
    for (int h = 0; h < N; h += 8) {
      const __m512d ov = _mm512_load_pd(o[a] + h), dv = _mm512_load_pd(d[a] + h);
      const __m512d inv = _mm512_div_pd(one, dv);
      const __m512d margin = _mm512_mul_pd(_mm512_mul_pd(_mm512_add_pd(extent, _mm512_abs_pd(ov)), _mm512_abs_pd(inv)), scale);
      const __m256 inv_f = _mm512_cvtpd_ps(inv);
      const __m512d minus_o = _mm512_castsi512_pd(
          _mm512_xor_si512(_mm512_castpd_si512(ov), _mm512_set1_epi64(std::int64_t(0x8000000000000000ull))));
      const __m256 offset = _mm512_cvtpd_ps(_mm512_mul_pd(minus_o, inv));
      const __m256 margin_f = _mm512_cvtpd_ps(margin);
      const __m256 near = _mm256_sub_ps(offset, margin_f), far = _mm256_add_ps(offset, margin_f);
      const __m256 ok = _mm256_and_ps(_mm256_and_ps(finite(inv_f), finite(offset)),
                                      _mm256_and_ps(finite(margin_f), _mm256_and_ps(finite(near), finite(far))));
      _mm256_store_ps(p.inv[a] + h, _mm256_and_ps(ok, inv_f));
      _mm256_store_ps(p.near_offset[a] + h, _mm256_blendv_ps(_mm256_sub_ps(_mm256_setzero_ps(), inf), near, ok));
      _mm256_store_ps(p.far_offset[a] + h, _mm256_blendv_ps(inf, far, ok));
    }
  }
  // round_down / round_up: the conversion rounding towards −∞ / +∞ gives the same floats (the
  // largest ≤ x / smallest ≥ x, ±FLT_MAX for finite x beyond float).
  alignas(64) double lo[N], hi[N];
  for (int i = 0; i < N; ++i) {
    const bool on = (active >> i) & 1u;
    lo[i] = on ? t_min[i] : std::numeric_limits<double>::infinity();  // an inactive lane meets no box
    hi[i] = on ? t_max[i] : -std::numeric_limits<double>::infinity();
  }
  for (int h = 0; h < N; h += 8) {
    _mm256_store_ps(p.t_min + h, _mm512_cvt_roundpd_ps(_mm512_load_pd(lo + h), _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
    _mm256_store_ps(p.t_max + h, _mm512_cvt_roundpd_ps(_mm512_load_pd(hi + h), _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC));
  }
#elif defined(STRAHL_PACKET_AVX2)
  // The same with AVX2: ray_boxes()'s double arithmetic four lanes at once, in its order. The
  // lanes' figures go into registers directly (scalar stores read back as a vector would stall).
  const __m256d one = _mm256_set1_pd(1.0), scale = _mm256_set1_pd(0x1p-21);
  const __m256d abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffll));
  const __m256d sign_d = _mm256_set1_pd(-0.0);
  const __m128 inf = _mm_set1_ps(std::numeric_limits<float>::infinity());
  const __m128 sign = _mm_set1_ps(-0.0f);
  const auto finite = [&](__m128 x) { return _mm_cmp_ps(_mm_andnot_ps(sign, x), inf, _CMP_LT_OQ); };
  const __m256i bit4 = _mm256_setr_epi64x(1, 2, 4, 8);
  unsigned negative[3] = {0, 0, 0};
  for (int h = 0; h < N; h += 4) {
    const __m256d on =
        _mm256_castsi256_pd(_mm256_cmpeq_epi64(_mm256_and_si256(_mm256_set1_epi64x((active >> h) & 15u), bit4), bit4));
    const Ray* r = rays + h;
    const __m256d ox = _mm256_set_pd(r[3].origin.x, r[2].origin.x, r[1].origin.x, r[0].origin.x);
    const __m256d oy = _mm256_set_pd(r[3].origin.y, r[2].origin.y, r[1].origin.y, r[0].origin.y);
    const __m256d oz = _mm256_set_pd(r[3].origin.z, r[2].origin.z, r[1].origin.z, r[0].origin.z);
    const __m256d dx = _mm256_set_pd(r[3].direction.x, r[2].direction.x, r[1].direction.x, r[0].direction.x);
    const __m256d dy = _mm256_set_pd(r[3].direction.y, r[2].direction.y, r[1].direction.y, r[0].direction.y);
    const __m256d dz = _mm256_set_pd(r[3].direction.z, r[2].direction.z, r[1].direction.z, r[0].direction.z);
    const __m256d o_axis[3] = {ox, oy, oz}, d_axis[3] = {dx, dy, dz};
    for (int a = 0; a < 3; ++a) {
      const __m256d ov = _mm256_and_pd(o_axis[a], on), dv = _mm256_blendv_pd(one, d_axis[a], on);
      negative[a] |= unsigned(_mm256_movemask_pd(dv)) << h;
      const __m256d extent = _mm256_set1_pd(Real(bvh.extent[a]));
      const __m256d inv = _mm256_div_pd(one, dv);
      const __m256d margin = _mm256_mul_pd(
          _mm256_mul_pd(_mm256_add_pd(extent, _mm256_and_pd(ov, abs_mask)), _mm256_and_pd(inv, abs_mask)), scale);
      const __m128 inv_f = _mm256_cvtpd_ps(inv);
      const __m128 offset = _mm256_cvtpd_ps(_mm256_mul_pd(_mm256_xor_pd(ov, sign_d), inv));
      const __m128 margin_f = _mm256_cvtpd_ps(margin);
      const __m128 near = _mm_sub_ps(offset, margin_f), far = _mm_add_ps(offset, margin_f);
      const __m128 ok = _mm_and_ps(_mm_and_ps(finite(inv_f), finite(offset)),
                                   _mm_and_ps(finite(margin_f), _mm_and_ps(finite(near), finite(far))));
      _mm_store_ps(p.inv[a] + h, _mm_and_ps(ok, inv_f));
      _mm_store_ps(p.near_offset[a] + h, _mm_blendv_ps(_mm_sub_ps(_mm_setzero_ps(), inf), near, ok));
      _mm_store_ps(p.far_offset[a] + h, _mm_blendv_ps(inf, far, ok));
    }
  }
  // Bit a of signs: every active lane's direction negative along a (−1: they differ along some axis).
  int all_sign = 0;
  p.signs = 0;
  for (int a = 0; a < 3; ++a) {
    const unsigned m = negative[a] & active;
    if (m == active) all_sign |= 1 << a;
    else if (m != 0) all_sign = -8;
  }
  p.signs = all_sign < 0 || active == 0 ? -1 : all_sign;
  // round_down / round_up four at a time (round_out4()).
  const __m256d pinf = _mm256_set1_pd(std::numeric_limits<double>::infinity());
  for (int h = 0; h < N; h += 4) {  // an inactive lane meets no box: t_min = +∞, t_max = −∞
    const __m256d on =
        _mm256_castsi256_pd(_mm256_cmpeq_epi64(_mm256_and_si256(_mm256_set1_epi64x((active >> h) & 15u), bit4), bit4));
    const __m256d lo = _mm256_blendv_pd(pinf, _mm256_loadu_pd(t_min + h), on);
    const __m256d hi = _mm256_blendv_pd(_mm256_sub_pd(_mm256_setzero_pd(), pinf), _mm256_loadu_pd(t_max + h), on);
    _mm_store_ps(p.t_min + h, round_out4<false>(lo));
    _mm_store_ps(p.t_max + h, round_out4<true>(hi));
  }
#else
  p.signs = shared_signs<N>(active, rays);
  for (int i = 0; i < N; ++i) {
    if ((active >> i) & 1u)
      set_lane(p, i, bvh, rays[i], t_min[i], t_max[i]);
    else
      clear_lane(p, i);
  }
#endif
  set_frustum(p, active);
}

#if defined(STRAHL_PACKET_AVX2)
// Eight lanes (from `first`) against child k: the mask of lanes whose ray meets the box, and the
// smallest entry distance among them (+∞ when none).
template <int N, bool kNear = true>
STRAHL_FORCE_INLINE unsigned child_test8(const WideBvhNode& n, int k, const PacketBoxes<N>& p, int first,
                                         unsigned lanes8, float& t_near) {
  const __m256 inf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
  __m256 tn = _mm256_load_ps(p.t_min + first), tf = _mm256_load_ps(p.t_max + first);
  // Axes z, y, x accumulated as in the single-ray test: max(x, max(y, max(z, t_min))). NaN (0·∞)
  // in an axis's figure: max/min return the second operand, the bound so far.
  if (p.signs >= 0) {  // one near plane for every lane: near·inv is min(lo·inv, hi·inv)
    for (int a = 2; a >= 0; --a) {
      const bool negative = (p.signs >> a) & 1;
      const __m256 inv = _mm256_load_ps(p.inv[a] + first);
      const __m256 t0 = _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(negative ? n.hi[a][k] : n.lo[a][k]), inv),
                                      _mm256_load_ps(p.near_offset[a] + first));
      const __m256 t1 = _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(negative ? n.lo[a][k] : n.hi[a][k]), inv),
                                      _mm256_load_ps(p.far_offset[a] + first));
      tn = _mm256_max_ps(t0, tn);
      tf = _mm256_min_ps(t1, tf);
    }
  } else {
    for (int a = 2; a >= 0; --a) {
      const __m256 inv = _mm256_load_ps(p.inv[a] + first);
      const __m256 lo = _mm256_mul_ps(_mm256_set1_ps(n.lo[a][k]), inv);
      const __m256 hi = _mm256_mul_ps(_mm256_set1_ps(n.hi[a][k]), inv);
      const __m256 t0 = _mm256_add_ps(_mm256_min_ps(lo, hi), _mm256_load_ps(p.near_offset[a] + first));
      const __m256 t1 = _mm256_add_ps(_mm256_max_ps(lo, hi), _mm256_load_ps(p.far_offset[a] + first));
      tn = _mm256_max_ps(t0, tn);
      tf = _mm256_min_ps(t1, tf);
    }
  }
  const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  const __m256 on = _mm256_castsi256_ps(
      _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(lanes8)), bit), bit));
  const __m256 hit = _mm256_and_ps(_mm256_cmp_ps(tn, tf, _CMP_LE_OQ), on);
  const unsigned mask = unsigned(_mm256_movemask_ps(hit));
  if (kNear && mask != 0) {
    const __m256 v = _mm256_blendv_ps(inf, tn, hit);
    __m128 m = _mm_min_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
    m = _mm_min_ps(m, _mm_movehl_ps(m, m));
    m = _mm_min_ss(m, _mm_shuffle_ps(m, m, 1));
    t_near = _mm_cvtss_f32(m);
  }
  return mask;
}
#endif

// Child k of node n against the packet's lanes in `lanes`: the lanes whose ray meets its box
// within their interval, and the smallest entry distance among them.
template <int N, bool kNear = true>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE std::uint32_t child_test(const WideBvhNode& n, int k, const PacketBoxes<N>& p,
                                                                std::uint32_t lanes, float& t_near) {
#if defined(STRAHL_PACKET_AVX512)
  if constexpr (N == 16) {
    __m512 tn = _mm512_load_ps(p.t_min), tf = _mm512_load_ps(p.t_max);
    if (p.signs >= 0) {  // one near plane for every lane: near·inv is min(lo·inv, hi·inv)
      for (int a = 2; a >= 0; --a) {
        const bool negative = (p.signs >> a) & 1;
        const __m512 inv = _mm512_load_ps(p.inv[a]);
        const __m512 t0 = _mm512_add_ps(_mm512_mul_ps(_mm512_set1_ps(negative ? n.hi[a][k] : n.lo[a][k]), inv),
                                        _mm512_load_ps(p.near_offset[a]));
        const __m512 t1 = _mm512_add_ps(_mm512_mul_ps(_mm512_set1_ps(negative ? n.lo[a][k] : n.hi[a][k]), inv),
                                        _mm512_load_ps(p.far_offset[a]));
        tn = _mm512_max_ps(t0, tn);
        tf = _mm512_min_ps(t1, tf);
      }
    } else {
      for (int a = 2; a >= 0; --a) {
        const __m512 inv = _mm512_load_ps(p.inv[a]);
        const __m512 lo = _mm512_mul_ps(_mm512_set1_ps(n.lo[a][k]), inv);
        const __m512 hi = _mm512_mul_ps(_mm512_set1_ps(n.hi[a][k]), inv);
        const __m512 t0 = _mm512_add_ps(_mm512_min_ps(lo, hi), _mm512_load_ps(p.near_offset[a]));
        const __m512 t1 = _mm512_add_ps(_mm512_max_ps(lo, hi), _mm512_load_ps(p.far_offset[a]));
        tn = _mm512_max_ps(t0, tn);
        tf = _mm512_min_ps(t1, tf);
      }
    }
    const __mmask16 hit = _mm512_mask_cmp_ps_mask(__mmask16(lanes), tn, tf, _CMP_LE_OQ);
    if (kNear && hit != 0) {
      // The smallest tn among the lanes hit (no _mm512_mask_reduce_min_ps: GCC 12 warns about
      // its undefined vectors).
      const __m512 v = _mm512_mask_blend_ps(hit, _mm512_set1_ps(std::numeric_limits<float>::infinity()), tn);
      const __m512 h = _mm512_min_ps(v, _mm512_shuffle_f32x4(v, v, 0xee));
      const __m256 q = _mm512_castps512_ps256(h);
      __m128 m = _mm_min_ps(_mm256_castps256_ps128(q), _mm256_extractf128_ps(q, 1));
      m = _mm_min_ps(m, _mm_movehl_ps(m, m));
      m = _mm_min_ss(m, _mm_shuffle_ps(m, m, 1));
      t_near = _mm_cvtss_f32(m);
    }
    return hit;
  }
#endif
#if defined(STRAHL_PACKET_AVX2)
  if constexpr (N % 8 == 0) {
    std::uint32_t hit = 0;
    t_near = std::numeric_limits<float>::infinity();
    for (int first = 0; first < N; first += 8) {
      if (((lanes >> first) & 0xffu) == 0) continue;
      float t = 0;
      const std::uint32_t m = child_test8<N, kNear>(n, k, p, first, (lanes >> first) & 0xffu, t);
      if (m != 0) {
        hit |= m << first;
        if (kNear) t_near = t < t_near ? t : t_near;
      }
    }
    return hit;
  }
#endif
  std::uint32_t hit = 0;
  float best = std::numeric_limits<float>::infinity();
  for (int i = 0; i < N; ++i) {
    if (((lanes >> i) & 1u) == 0) continue;
    float lo = p.t_min[i], hi = p.t_max[i];
    for (int a = 2; a >= 0; --a) {
      const float l = n.lo[a][k] * p.inv[a][i], h = n.hi[a][k] * p.inv[a][i];
      const float t0 = (l < h ? l : h) + p.near_offset[a][i];  // NaN: h, as min_ps
      const float t1 = (l > h ? l : h) + p.far_offset[a][i];
      lo = t0 > lo ? t0 : lo;  // NaN keeps the bound
      hi = t1 < hi ? t1 : hi;
    }
    if (lo <= hi) {
      hit |= 1u << i;
      best = lo < best ? lo : best;
    }
  }
  t_near = best;
  return hit;
}

// The lanes of `lanes` whose t_max (float, rounded up) is ≥ t: those a box entered at t may still serve.
template <int N>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE std::uint32_t lanes_reaching(const PacketBoxes<N>& p, std::uint32_t lanes,
                                                                    float t) {
#if defined(STRAHL_PACKET_AVX512)
  if constexpr (N == 16)
    return _mm512_mask_cmp_ps_mask(__mmask16(lanes), _mm512_set1_ps(t), _mm512_load_ps(p.t_max), _CMP_LE_OQ);
#endif
#if defined(STRAHL_PACKET_AVX2)
  if constexpr (N % 8 == 0) {
    std::uint32_t m = 0;
    for (int first = 0; first < N; first += 8)
      m |= std::uint32_t(_mm256_movemask_ps(
               _mm256_cmp_ps(_mm256_set1_ps(t), _mm256_load_ps(p.t_max + first), _CMP_LE_OQ)))
           << first;
    return m & lanes;
  }
#endif
  std::uint32_t m = 0;
  for (int i = 0; i < N; ++i)
    if (((lanes >> i) & 1u) && t <= p.t_max[i]) m |= 1u << i;
  return m;
}

}  // namespace strahl::wide_bvh_packet_detail

STRAHL_PACKET_WARNINGS_ON
