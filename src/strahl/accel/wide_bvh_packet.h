#pragma once
// Packets of N = 8 or 16 coherent rays (a tile of neighbouring pixels' primary rays, the shadow
// rays from their hits to one light) through the wide BVH of wide_bvh.h together: each node is
// fetched once per packet; its eight child boxes are first tested at once against the packet's
// frustum (frustum_children(): per axis the lanes' extreme figures, a necessary condition for any
// lane to meet a box), and only the children that pass are tested against all the packet's rays
// with SIMD across the rays (AVX-512: 16 lanes; AVX2: 8; else a scalar loop). A child is visited
// with the mask of the lanes whose ray meets its box, nearest first by the frustum's entry
// distance (a lower bound of every lane's); a waiting box is dropped, lane by lane, once that
// distance lies beyond a lane's nearest hit (or the lane is occluded).
//
// In the leaves, each lane's ray meets the triangles with exactly the IEEE operations of the
// single-ray block test (kernel::blocks_nearest / blocks_any of triangle_block.h): lane by lane
// with its own ray, or (see "the leaves" below) four or eight lanes with one axis order against
// one triangle at a time. The answers are those of wide_bvh_nearest() and wide_bvh_occluded() bit
// for bit — the same t, barycentrics and primitive — except where two primitives are hit at
// exactly the same t (a ray through a shared edge or vertex): then which of them is reported
// depends on the order the leaves are visited in, which differs between a ray alone and a ray in
// a packet (the t is the same).
//
// The float box test is the conservative one of wide_bvh.h (ray_boxes(): the same margins, the
// same figures, computed four or eight lanes at once where SIMD is built), with the near and far
// planes chosen per lane by min/max instead of by the direction's sign (or, where every lane's
// signs agree, the planes the signs pick), which gives the same figures.
//
// Plain structs, a fixed stack, no allocation: the same code compiles for the device (scalar path).

#include <cstdint>

#include "strahl/accel/primitive.h"
#include "strahl/accel/triangle_block.h"
#include "strahl/accel/wide_bvh.h"

// STRAHL_PORTABLE_KERNELS: the scalar path on a SIMD host too (the tests compare them).
#if !defined(__CUDACC__) && defined(__AVX2__) && !defined(STRAHL_PORTABLE_KERNELS)
#include <immintrin.h>
#define STRAHL_PACKET_AVX2 1
#if defined(__AVX512F__)
#define STRAHL_PACKET_AVX512 1
#endif
#endif

// GCC 12 warns about the undefined vectors inside its own AVX-512 intrinsics (GCC bug 105593)
// wherever they are inlined; the warning is off for this header only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#endif

namespace strahl {

inline constexpr int kMaxPacketSize = 16;

namespace wide_bvh_packet_detail {

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

// ---- the leaves: one triangle against the packet's rays at once (AVX-512 / AVX2, double) ----
//
// Lanes whose rays shear with the same axis order (kx, ky, kz: the usual case in a coherent
// packet) test each triangle of a leaf together, with exactly the IEEE operations of
// kernel::intersect() in its order (as triangle_block.h's test, which is bit for bit the scalar
// test), so each lane's t, b1, b2 are the single ray's. The triangles are scanned in block and
// lane order accepting t < the lane's nearest so far, which finds what blocks_nearest() finds:
// the first of the nearest. AVX-512: every group of lanes with one axis order, eight at a time,
// nearest and any hit. AVX2 (four lanes a vector: no fewer operations per lane and triangle than
// one ray against a block of four): only groups of three or four of a vector's lanes, for nearest
// hits, where it measured faster. Leaves with spheres or solids, and the other lanes, go lane by lane through
// blocks_nearest() / blocks_any().

// Per lane, structure of arrays, in double: the origin in the lane's axis order, the shear, the
// interval, and the nearest hit so far.
template <int N>
struct alignas(64) PacketTriangles {
  double o[3][N];
  double s[3][N];  // sx, sy, sz
  double t_min[N];
  double t_far[N];  // the nearest hit's t so far (the interval's end before any)
  double b1[N], b2[N];
  std::uint32_t prim[N];
  std::uint8_t axes[N];  // the lane's axis order: kx | ky << 2 | kz << 4
};

template <int N>
STRAHL_HOST_DEVICE inline void set_triangle_lanes(PacketTriangles<N>& q, std::uint32_t active,
                                                  const kernel::TriangleBlockRay* br, const Real* t_min,
                                                  const Real* t_max) {
  for (int i = 0; i < N; ++i) {
    q.t_far[i] = 0;
    q.b1[i] = q.b2[i] = 0;
    q.prim[i] = 0;
    q.t_min[i] = 0;
    q.axes[i] = 0;
    for (int a = 0; a < 3; ++a) q.o[a][i] = q.s[a][i] = 0;
    if (((active >> i) & 1u) == 0) continue;
    const kernel::RayShear& s = br[i].shear;
    q.axes[i] = std::uint8_t(s.kx | s.ky << 2 | s.kz << 4);
    for (int a = 0; a < 3; ++a) q.o[a][i] = br[i].o[a];
    q.s[0][i] = s.sx;
    q.s[1][i] = s.sy;
    q.s[2][i] = s.sz;
    q.t_min[i] = t_min[i];
    q.t_far[i] = t_max[i];
  }
}

#if defined(STRAHL_PACKET_AVX512)
// Eight lanes from `first` (mask m8) against every triangle of the leaf's blocks. any: stop a lane
// at its first hit (returns the lanes hit); else keep the nearest (returns the lanes whose nearest
// changed).
template <int N>
STRAHL_FORCE_INLINE unsigned leaf_triangles8(const WideBvhLeaf* blocks, std::uint32_t count, PacketTriangles<N>& q,
                                             int first, unsigned m8, bool any, int kx, int ky, int kz) {
  const __m512d ox = _mm512_load_pd(q.o[0] + first), oy = _mm512_load_pd(q.o[1] + first),
                oz = _mm512_load_pd(q.o[2] + first);
  const __m512d sx = _mm512_load_pd(q.s[0] + first), sy = _mm512_load_pd(q.s[1] + first),
                sz = _mm512_load_pd(q.s[2] + first);
  const __m512d t_min = _mm512_load_pd(q.t_min + first);
  __m512d t_far = _mm512_load_pd(q.t_far + first);
  __m512d b1 = _mm512_load_pd(q.b1 + first), b2 = _mm512_load_pd(q.b2 + first);
  __m256i prim = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(q.prim + first));
  const __m512d zero = _mm512_setzero_pd();
  __mmask8 live = __mmask8(m8), changed = 0;
  for (std::uint32_t bi = 0; bi < count && live != 0; ++bi) {
    const WideBvhLeaf& b = blocks[bi];
    unsigned tri = b.triangles;
    while (tri != 0 && live != 0) {
      const int k = wide_bvh_detail::lowest_bit(tri);
      tri &= tri - 1;
      // shear_triangle(): a = v0 − o (components kx, ky, kz), ax = a[kx] − sx·a[kz], ...
      const __m512d a_x = _mm512_sub_pd(_mm512_set1_pd(b.v[0][kx][k]), ox);
      const __m512d a_y = _mm512_sub_pd(_mm512_set1_pd(b.v[0][ky][k]), oy);
      const __m512d a_z = _mm512_sub_pd(_mm512_set1_pd(b.v[0][kz][k]), oz);
      const __m512d b_x = _mm512_sub_pd(_mm512_set1_pd(b.v[1][kx][k]), ox);
      const __m512d b_y = _mm512_sub_pd(_mm512_set1_pd(b.v[1][ky][k]), oy);
      const __m512d b_z = _mm512_sub_pd(_mm512_set1_pd(b.v[1][kz][k]), oz);
      const __m512d c_x = _mm512_sub_pd(_mm512_set1_pd(b.v[2][kx][k]), ox);
      const __m512d c_y = _mm512_sub_pd(_mm512_set1_pd(b.v[2][ky][k]), oy);
      const __m512d c_z = _mm512_sub_pd(_mm512_set1_pd(b.v[2][kz][k]), oz);
      const __m512d ax = _mm512_sub_pd(a_x, _mm512_mul_pd(sx, a_z)), ay = _mm512_sub_pd(a_y, _mm512_mul_pd(sy, a_z));
      const __m512d bx = _mm512_sub_pd(b_x, _mm512_mul_pd(sx, b_z)), by = _mm512_sub_pd(b_y, _mm512_mul_pd(sy, b_z));
      const __m512d cx = _mm512_sub_pd(c_x, _mm512_mul_pd(sx, c_z)), cy = _mm512_sub_pd(c_y, _mm512_mul_pd(sy, c_z));
      const __m512d u = _mm512_sub_pd(_mm512_mul_pd(cx, by), _mm512_mul_pd(cy, bx));
      const __m512d v = _mm512_sub_pd(_mm512_mul_pd(ax, cy), _mm512_mul_pd(ay, cx));
      const __m512d w = _mm512_sub_pd(_mm512_mul_pd(bx, ay), _mm512_mul_pd(by, ax));
      const __mmask8 negative = _mm512_cmp_pd_mask(u, zero, _CMP_LT_OQ) | _mm512_cmp_pd_mask(v, zero, _CMP_LT_OQ) |
                                _mm512_cmp_pd_mask(w, zero, _CMP_LT_OQ);
      const __mmask8 positive = _mm512_cmp_pd_mask(u, zero, _CMP_GT_OQ) | _mm512_cmp_pd_mask(v, zero, _CMP_GT_OQ) |
                                _mm512_cmp_pd_mask(w, zero, _CMP_GT_OQ);
      const __m512d det = _mm512_add_pd(_mm512_add_pd(u, v), w);
      const __mmask8 inside = __mmask8(live & ~(negative & positive) & _mm512_cmp_pd_mask(det, zero, _CMP_NEQ_OQ));
      if (inside == 0) continue;
      const __m512d inv_det = _mm512_div_pd(_mm512_set1_pd(1.0), det);
      // sheared_distance(): az = sz·a[kz], ..., t = (u·az + v·bz + w·cz)·inv_det.
      const __m512d az = _mm512_mul_pd(sz, a_z), bz = _mm512_mul_pd(sz, b_z), cz = _mm512_mul_pd(sz, c_z);
      const __m512d t = _mm512_mul_pd(
          _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(u, az), _mm512_mul_pd(v, bz)), _mm512_mul_pd(w, cz)), inv_det);
      const __mmask8 hit = inside & _mm512_cmp_pd_mask(t, t_min, _CMP_GT_OQ) & _mm512_cmp_pd_mask(t, t_far, _CMP_LT_OQ);
      if (hit == 0) continue;
      if (any) {
        changed |= hit;
        live &= __mmask8(~hit);
        continue;
      }
      changed |= hit;
      t_far = _mm512_mask_mov_pd(t_far, hit, t);
      b1 = _mm512_mask_mov_pd(b1, hit, _mm512_mul_pd(v, inv_det));
      b2 = _mm512_mask_mov_pd(b2, hit, _mm512_mul_pd(w, inv_det));
      prim = _mm256_mask_mov_epi32(prim, hit, _mm256_set1_epi32(int(b.prim[k])));
    }
  }
  if (!any && changed != 0) {
    _mm512_store_pd(q.t_far + first, t_far);
    _mm512_store_pd(q.b1 + first, b1);
    _mm512_store_pd(q.b2 + first, b2);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(q.prim + first), prim);
  }
  return changed;
}

// The lanes of `lanes` against every triangle of the leaf, eight at a time, each group of lanes
// with one axis order in a call of its own (a coherent packet has one or two).
template <int N>
STRAHL_FORCE_INLINE std::uint32_t leaf_triangles(const WideBvhLeaf* blocks, std::uint32_t count,
                                                 PacketTriangles<N>& q, std::uint32_t lanes, bool any) {
  std::uint32_t changed = 0;
  for (int h = 0; h < N; h += 8) {
    unsigned m8 = (lanes >> h) & 0xffu;
    while (m8 != 0) {
      const int axes = q.axes[h + wide_bvh_detail::lowest_bit(m8)];
      unsigned group = 0;
      for (unsigned m = m8; m != 0; m &= m - 1) {
        const int i = wide_bvh_detail::lowest_bit(m);
        if (q.axes[h + i] == axes) group |= 1u << i;
      }
      m8 &= ~group;
      changed |= std::uint32_t(leaf_triangles8(blocks, count, q, h, group, any, axes & 3, (axes >> 2) & 3, axes >> 4))
                 << h;
    }
  }
  return changed;
}
#endif

#if defined(STRAHL_PACKET_AVX2) && !defined(STRAHL_PACKET_AVX512)
// Four lanes from `first` (mask m4, one axis order kx, ky, kz) against every triangle of the
// leaf's blocks, a triangle at a time, with exactly the IEEE operations of kernel::intersect() in
// its order (as leaf_triangles8()); the nearest hit per lane (returns the lanes whose nearest
// changed).
template <int N>
STRAHL_FORCE_INLINE unsigned leaf_triangles4(const WideBvhLeaf* blocks, std::uint32_t count, PacketTriangles<N>& q,
                                             int first, unsigned m4, int kx, int ky, int kz) {
  const __m256d ox = _mm256_load_pd(q.o[0] + first), oy = _mm256_load_pd(q.o[1] + first),
                oz = _mm256_load_pd(q.o[2] + first);
  const __m256d sx = _mm256_load_pd(q.s[0] + first), sy = _mm256_load_pd(q.s[1] + first),
                sz = _mm256_load_pd(q.s[2] + first);
  const __m256d t_min = _mm256_load_pd(q.t_min + first);
  __m256d t_far = _mm256_load_pd(q.t_far + first);
  const __m256d zero = _mm256_setzero_pd();
  const __m256i bit = _mm256_setr_epi64x(1, 2, 4, 8);
  const __m256d live =
      _mm256_castsi256_pd(_mm256_cmpeq_epi64(_mm256_and_si256(_mm256_set1_epi64x(std::int64_t(m4)), bit), bit));
  unsigned changed = 0;
  for (std::uint32_t bi = 0; bi < count; ++bi) {
    const WideBvhLeaf& b = blocks[bi];
    for (unsigned tri = b.triangles; tri != 0; tri &= tri - 1) {
      const int k = wide_bvh_detail::lowest_bit(tri);
      // shear_triangle(): a = v0 − o (components kx, ky, kz), ax = a[kx] − sx·a[kz], ...
      const __m256d a_x = _mm256_sub_pd(_mm256_broadcast_sd(&b.v[0][kx][k]), ox);
      const __m256d a_y = _mm256_sub_pd(_mm256_broadcast_sd(&b.v[0][ky][k]), oy);
      const __m256d a_z = _mm256_sub_pd(_mm256_broadcast_sd(&b.v[0][kz][k]), oz);
      const __m256d b_x = _mm256_sub_pd(_mm256_broadcast_sd(&b.v[1][kx][k]), ox);
      const __m256d b_y = _mm256_sub_pd(_mm256_broadcast_sd(&b.v[1][ky][k]), oy);
      const __m256d b_z = _mm256_sub_pd(_mm256_broadcast_sd(&b.v[1][kz][k]), oz);
      const __m256d c_x = _mm256_sub_pd(_mm256_broadcast_sd(&b.v[2][kx][k]), ox);
      const __m256d c_y = _mm256_sub_pd(_mm256_broadcast_sd(&b.v[2][ky][k]), oy);
      const __m256d c_z = _mm256_sub_pd(_mm256_broadcast_sd(&b.v[2][kz][k]), oz);
      const __m256d ax = _mm256_sub_pd(a_x, _mm256_mul_pd(sx, a_z)), ay = _mm256_sub_pd(a_y, _mm256_mul_pd(sy, a_z));
      const __m256d bx = _mm256_sub_pd(b_x, _mm256_mul_pd(sx, b_z)), by = _mm256_sub_pd(b_y, _mm256_mul_pd(sy, b_z));
      const __m256d cx = _mm256_sub_pd(c_x, _mm256_mul_pd(sx, c_z)), cy = _mm256_sub_pd(c_y, _mm256_mul_pd(sy, c_z));
      const __m256d u = _mm256_sub_pd(_mm256_mul_pd(cx, by), _mm256_mul_pd(cy, bx));
      const __m256d v = _mm256_sub_pd(_mm256_mul_pd(ax, cy), _mm256_mul_pd(ay, cx));
      const __m256d w = _mm256_sub_pd(_mm256_mul_pd(bx, ay), _mm256_mul_pd(by, ax));
      const __m256d negative =
          _mm256_or_pd(_mm256_cmp_pd(u, zero, _CMP_LT_OQ),
                       _mm256_or_pd(_mm256_cmp_pd(v, zero, _CMP_LT_OQ), _mm256_cmp_pd(w, zero, _CMP_LT_OQ)));
      const __m256d positive =
          _mm256_or_pd(_mm256_cmp_pd(u, zero, _CMP_GT_OQ),
                       _mm256_or_pd(_mm256_cmp_pd(v, zero, _CMP_GT_OQ), _mm256_cmp_pd(w, zero, _CMP_GT_OQ)));
      const __m256d det = _mm256_add_pd(_mm256_add_pd(u, v), w);
      const __m256d inside = _mm256_and_pd(
          _mm256_andnot_pd(_mm256_and_pd(negative, positive), _mm256_cmp_pd(det, zero, _CMP_NEQ_OQ)), live);
      if (_mm256_movemask_pd(inside) == 0) continue;
      const __m256d inv_det = _mm256_div_pd(_mm256_set1_pd(1.0), det);
      // sheared_distance(): az = sz·a[kz], ..., t = (u·az + v·bz + w·cz)·inv_det.
      const __m256d az = _mm256_mul_pd(sz, a_z), bz = _mm256_mul_pd(sz, b_z), cz = _mm256_mul_pd(sz, c_z);
      const __m256d t = _mm256_mul_pd(
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(u, az), _mm256_mul_pd(v, bz)), _mm256_mul_pd(w, cz)), inv_det);
      const __m256d hit = _mm256_and_pd(
          inside, _mm256_and_pd(_mm256_cmp_pd(t, t_min, _CMP_GT_OQ), _mm256_cmp_pd(t, t_far, _CMP_LT_OQ)));
      const unsigned hit_bits = unsigned(_mm256_movemask_pd(hit));
      if (hit_bits == 0) continue;
      changed |= hit_bits;
      t_far = _mm256_blendv_pd(t_far, t, hit);
      alignas(32) double b1v[4], b2v[4];
      _mm256_store_pd(b1v, _mm256_mul_pd(v, inv_det));
      _mm256_store_pd(b2v, _mm256_mul_pd(w, inv_det));
      for (unsigned m = hit_bits; m != 0; m &= m - 1) {
        const int i = wide_bvh_detail::lowest_bit(m);
        q.b1[first + i] = b1v[i];
        q.b2[first + i] = b2v[i];
        q.prim[first + i] = b.prim[k];
      }
    }
  }
  if (changed != 0) _mm256_store_pd(q.t_far + first, t_far);
  return changed;
}

// The nearest hits of the lanes of `lanes` that come three or four to a vector's four lanes, all
// with one axis order (leaf_triangles4()); `lanes` keeps the others, for the one-lane blocks test.
// (Two lanes a vector measured slower than the one-lane test.)
template <int N>
STRAHL_FORCE_INLINE std::uint32_t leaf_triangles_dense(const WideBvhLeaf* blocks, std::uint32_t count,
                                                       PacketTriangles<N>& q, std::uint32_t& lanes) {
  std::uint32_t changed = 0;
  for (int h = 0; h < N; h += 4) {
    const unsigned m4 = (lanes >> h) & 15u;
    if (m4 == 0 || (m4 & (m4 - 1)) == 0 || ((m4 & (m4 - 1)) & ((m4 & (m4 - 1)) - 1)) == 0) continue;  // < 3 lanes
    const int axes = q.axes[h + wide_bvh_detail::lowest_bit(m4)];
    unsigned group = 0;
    for (int i = 0; i < 4; ++i)
      if (((m4 >> i) & 1u) && q.axes[h + i] == axes) group |= 1u << i;
    if (group != m4) continue;
    changed |= std::uint32_t(leaf_triangles4(blocks, count, q, h, group, axes & 3, (axes >> 2) & 3, axes >> 4)) << h;
    lanes &= ~(group << h);
  }
  return changed;
}
#endif

// Does every block of the leaf hold triangles only (no sphere or solid lanes)?
STRAHL_HOST_DEVICE inline bool triangles_only(const WideBvhLeaf* blocks, std::uint32_t count) {
  std::uint32_t other = 0;
  for (std::uint32_t i = 0; i < count; ++i) other |= blocks[i].other;
  return other == 0;
}

// The children of node n (a bit per slot, empty slots never set) whose box some lane of the packet
// may meet: a necessary condition, so that only these need child_test(). A lane meets a box where
// max over the axes of its entry figure t0 (and t_min) ≤ min of its exit figure t1 (and t_max),
// t0 = fl(min(fl(lo·inv), fl(hi·inv)) + near_offset), t1 likewise with max and far_offset (a NaN
// figure constrains nothing). Float rounding is monotone and x·inv is monotone in inv, so with inv
// within [f_inv_lo, f_inv_hi] and near_offset ≥ f_near, t0 ≥ fl(min of the four products
// lo·f_inv_lo, lo·f_inv_hi, hi·f_inv_lo, hi·f_inv_hi + f_near) (and t1 ≤ the like with max and
// f_far): the box of a child some lane meets passes. A lane whose axis is unconstrained (inv 0,
// near_offset −∞) makes f_near −∞, and the frustum unconstrained along it too.
template <int N>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE unsigned frustum_children(const WideBvhNode& n, const PacketBoxes<N>& p,
                                                                  float* t_front) {
#if defined(STRAHL_PACKET_AVX2)
  static_assert(kWideBvhWidth == 8);
  __m256 tn = _mm256_set1_ps(p.f_t_min), tf = _mm256_set1_ps(p.f_t_max);
  for (int a = 2; a >= 0; --a) {
    const __m256 lo = _mm256_load_ps(n.lo[a]), hi = _mm256_load_ps(n.hi[a]);
    const __m256 il = _mm256_set1_ps(p.f_inv_lo[a]), ih = _mm256_set1_ps(p.f_inv_hi[a]);
    const __m256 p0 = _mm256_mul_ps(lo, il), p1 = _mm256_mul_ps(lo, ih);
    const __m256 p2 = _mm256_mul_ps(hi, il), p3 = _mm256_mul_ps(hi, ih);
    const __m256 mn = _mm256_min_ps(_mm256_min_ps(p0, p1), _mm256_min_ps(p2, p3));
    const __m256 mx = _mm256_max_ps(_mm256_max_ps(p0, p1), _mm256_max_ps(p2, p3));
    tn = _mm256_max_ps(_mm256_add_ps(mn, _mm256_set1_ps(p.f_near[a])), tn);
    tf = _mm256_min_ps(_mm256_add_ps(mx, _mm256_set1_ps(p.f_far[a])), tf);
  }
  const unsigned empty = unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(
      _mm256_cmpeq_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(n.child)), _mm256_set1_epi32(-1)))));
  _mm256_storeu_ps(t_front, tn);
  return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(tn, tf, _CMP_LE_OQ))) & ~empty;
#else
  unsigned mask = 0;
  for (int k = 0; k < kWideBvhWidth; ++k) {
    if (n.child[k] == kWideBvhEmpty) continue;
    float lo = p.f_t_min, hi = p.f_t_max;
    for (int a = 2; a >= 0; --a) {
      const float p0 = n.lo[a][k] * p.f_inv_lo[a], p1 = n.lo[a][k] * p.f_inv_hi[a];
      const float p2 = n.hi[a][k] * p.f_inv_lo[a], p3 = n.hi[a][k] * p.f_inv_hi[a];
      const float m01 = p0 < p1 ? p0 : p1, m23 = p2 < p3 ? p2 : p3;  // NaN: the second, as min_ps
      const float x01 = p0 > p1 ? p0 : p1, x23 = p2 > p3 ? p2 : p3;
      const float t0 = (m01 < m23 ? m01 : m23) + p.f_near[a];
      const float t1 = (x01 > x23 ? x01 : x23) + p.f_far[a];
      lo = t0 > lo ? t0 : lo;  // NaN keeps the bound
      hi = t1 < hi ? t1 : hi;
    }
    t_front[k] = lo;
    if (lo <= hi) mask |= 1u << k;
  }
  return mask;
#endif
}

// Calls leaf(first_block, count, lanes) for every leaf some lane's ray meets within its interval,
// with the mask of those lanes (a subset of `live`); leaf returns the lanes that are finished
// (occluded) and lowers p.t_max of lanes whose interval shrank. Nearer boxes first.
// kOrdered: children nearest first (nearest-hit queries); else in slot order, with t_near 0 (any
// hit: the intervals never shrink, so nothing is culled by distance and order matters little).
template <int N, bool kOrdered, class Leaf>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void traverse_packet(const WideBvhView& bvh, PacketBoxes<N>& p,
                                                            std::uint32_t live, Leaf& leaf) {
  using wide_bvh_detail::lowest_bit;
  if (live == 0) return;
  if (bvh.root_leaf_count > 0) {
    leaf(bvh.leaves, bvh.root_leaf_count, live);
    return;
  }
  if (bvh.nodes == nullptr) return;
  PacketStackEntry stack[(kWideBvhWidth - 1) * 64 + 4];
  int top = 0;
  std::uint32_t child = 0, count = 0, lanes = live;  // the root node, every live lane
  for (;;) {
    if (count == 0) {
      const WideBvhNode& n = bvh.nodes[child];
      std::uint32_t child_lanes[kWideBvhWidth];
      float t_near[kWideBvhWidth];
      int order[kWideBvhWidth], hits = 0;
      float t_front[kWideBvhWidth];
      for (unsigned candidates = frustum_children(n, p, t_front); candidates != 0; candidates &= candidates - 1) {
        const int k = lowest_bit(candidates);
        float t = 0;
        const std::uint32_t m = child_test<N, false>(n, k, p, lanes, t);
        if (m == 0) continue;
        t = kOrdered ? t_front[k] : 0;
        child_lanes[k] = m;
        t_near[k] = t;
        int j = hits++;  // insertion by entry distance, equal ones in slot order
        if (kOrdered)
          for (; j > 0 && t_near[order[j - 1]] > t; --j) order[j] = order[j - 1];
        order[j] = k;
      }
      if (hits > 0) {
        for (int i = hits - 1; i > 0; --i) {
          const int k = order[i];
          stack[top++] = {n.child[k], n.count[k], child_lanes[k], t_near[k]};
        }
        const int k = order[0];
        child = n.child[k];
        count = n.count[k];
        lanes = child_lanes[k];
        continue;
      }
    } else {
      live &= ~leaf(bvh.leaves + child, count, lanes);
      if (live == 0) return;
    }
    // The next waiting box that some live lane may still need.
    for (;;) {
      if (top == 0) return;
      const PacketStackEntry& e = stack[--top];
      const std::uint32_t m = kOrdered ? lanes_reaching(p, e.lanes & live, e.t_near) : e.lanes & live;
      if (m != 0) {
        child = e.child;
        count = e.count;
        lanes = m;
        break;
      }
    }
  }
}

// A packet query's state: the lanes' boxes, and what the triangle tests need, made when the first
// leaf is reached (a packet that misses every box never needs it).
template <int N>
struct PacketQuery {
  PacketBoxes<N> boxes;
  kernel::TriangleBlockRay block_rays[N];
  PacketTriangles<N> triangles;
  std::uint32_t active;
  const Ray* rays;
  const Real *t_min, *t_max;
  bool ready = false;

  STRAHL_HOST_DEVICE PacketQuery(const WideBvhView& bvh, std::uint32_t active_, const Ray* rays_, const Real* t_min_,
                                 const Real* t_max_)
      : active(active_), rays(rays_), t_min(t_min_), t_max(t_max_) {
    set_lanes(boxes, active, bvh, rays, t_min, t_max);
  }
  STRAHL_HOST_DEVICE void prepare() {
    if (ready) return;
#if defined(STRAHL_PACKET_AVX2)
    // kernel::ray_shear() of four lanes at once, with blends for its choices of axes and the same
    // three divisions (sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = 1 / d[kz]); inactive lanes
    // get zeros (direction (0, 0, 1)).
    PacketTriangles<N>& q = triangles;
    const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
    const __m256d abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffll));
    const __m256i bit4 = _mm256_setr_epi64x(1, 2, 4, 8);
    const auto select = [](__m256d if_kz0, __m256d if_kz1, __m256d if_kz2, __m256d kz0, __m256d kz1) {
      return _mm256_blendv_pd(_mm256_blendv_pd(if_kz2, if_kz1, kz1), if_kz0, kz0);
    };
    for (int h = 0; h < N; h += 4) {
      const unsigned bits = (active >> h) & 15u;
      const __m256d on = _mm256_castsi256_pd(_mm256_cmpeq_epi64(_mm256_and_si256(_mm256_set1_epi64x(bits), bit4), bit4));
      const Ray* r = rays + h;
      const __m256d ox = _mm256_and_pd(on, _mm256_set_pd(r[3].origin.x, r[2].origin.x, r[1].origin.x, r[0].origin.x));
      const __m256d oy = _mm256_and_pd(on, _mm256_set_pd(r[3].origin.y, r[2].origin.y, r[1].origin.y, r[0].origin.y));
      const __m256d oz = _mm256_and_pd(on, _mm256_set_pd(r[3].origin.z, r[2].origin.z, r[1].origin.z, r[0].origin.z));
      const __m256d dx = _mm256_and_pd(
          on, _mm256_set_pd(r[3].direction.x, r[2].direction.x, r[1].direction.x, r[0].direction.x));
      const __m256d dy = _mm256_and_pd(
          on, _mm256_set_pd(r[3].direction.y, r[2].direction.y, r[1].direction.y, r[0].direction.y));
      const __m256d dz = _mm256_blendv_pd(
          one, _mm256_set_pd(r[3].direction.z, r[2].direction.z, r[1].direction.z, r[0].direction.z), on);
      // kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2)
      const __m256d ax = _mm256_and_pd(dx, abs_mask), ay = _mm256_and_pd(dy, abs_mask), az = _mm256_and_pd(dz, abs_mask);
      const __m256d x_gt_y = _mm256_cmp_pd(ax, ay, _CMP_GT_OQ);
      const __m256d kz0 = _mm256_and_pd(x_gt_y, _mm256_cmp_pd(ax, az, _CMP_GT_OQ));
      const __m256d kz1 = _mm256_andnot_pd(x_gt_y, _mm256_cmp_pd(ay, az, _CMP_GT_OQ));
      // kx, ky: the next two axes after kz, swapped where d[kz] < 0.
      const __m256d d_kz = select(dx, dy, dz, kz0, kz1);
      const __m256d swap = _mm256_cmp_pd(d_kz, zero, _CMP_LT_OQ);
      const __m256d d_next = select(dy, dz, dx, kz0, kz1), d_after = select(dz, dx, dy, kz0, kz1);
      const __m256d o_next = select(oy, oz, ox, kz0, kz1), o_after = select(oz, ox, oy, kz0, kz1);
      const __m256d d_kx = _mm256_blendv_pd(d_next, d_after, swap), d_ky = _mm256_blendv_pd(d_after, d_next, swap);
      _mm256_store_pd(q.o[0] + h, _mm256_blendv_pd(o_next, o_after, swap));
      _mm256_store_pd(q.o[1] + h, _mm256_blendv_pd(o_after, o_next, swap));
      _mm256_store_pd(q.o[2] + h, select(ox, oy, oz, kz0, kz1));
      _mm256_store_pd(q.s[0] + h, _mm256_div_pd(d_kx, d_kz));
      _mm256_store_pd(q.s[1] + h, _mm256_div_pd(d_ky, d_kz));
      _mm256_store_pd(q.s[2] + h, _mm256_div_pd(one, d_kz));
      _mm256_store_pd(q.t_min + h, _mm256_and_pd(on, _mm256_loadu_pd(t_min + h)));
      _mm256_store_pd(q.t_far + h, _mm256_blendv_pd(zero, _mm256_loadu_pd(t_max + h), on));
      _mm256_store_pd(q.b1 + h, zero);
      _mm256_store_pd(q.b2 + h, zero);
      const unsigned m0 = unsigned(_mm256_movemask_pd(kz0)), m1 = unsigned(_mm256_movemask_pd(kz1)),
                     ms = unsigned(_mm256_movemask_pd(swap));
      for (int i = 0; i < 4; ++i) {
        const int kz = (m0 >> i) & 1u ? 0 : ((m1 >> i) & 1u ? 1 : 2);
        const int next = kz == 2 ? 0 : kz + 1, after = next == 2 ? 0 : next + 1;
        const bool sw = (ms >> i) & 1u;
        q.axes[h + i] = ((bits >> i) & 1u) ? std::uint8_t((sw ? after : next) | (sw ? next : after) << 2 | kz << 4) : 0;
        q.prim[h + i] = 0;
      }
    }
    for (int i = 0; i < N; ++i) {
      if (((active >> i) & 1u) == 0) continue;
      kernel::TriangleBlockRay& br = block_rays[i];
      br.ray = rays[i];
      br.shear.kx = q.axes[i] & 3;
      br.shear.ky = (q.axes[i] >> 2) & 3;
      br.shear.kz = q.axes[i] >> 4;
      br.shear.sx = q.s[0][i];
      br.shear.sy = q.s[1][i];
      br.shear.sz = q.s[2][i];
      for (int a = 0; a < 3; ++a) br.o[a] = q.o[a][i];
    }
#else
    for (int i = 0; i < N; ++i)
      if ((active >> i) & 1u) block_rays[i] = kernel::triangle_block_ray(rays[i], kernel::ray_shear(rays[i].direction));
    set_triangle_lanes(triangles, active, block_rays, t_min, t_max);
#endif
    ready = true;
  }
};

}  // namespace wide_bvh_packet_detail

// The nearest hit of each active lane (bit i of `active`) in (t_min[i], t_max[i]), N = 8 or 16:
// like wide_bvh_nearest() on each ray — t_max[i] lowered to the hit's t, prim[i] and hit[i] set
// where a hit is found, left alone where none is (the caller sets hit[i].t = kInfinity first).
template <int N>
STRAHL_HOST_DEVICE inline void wide_bvh_nearest_packet(const WideBvhView& bvh, const PrimitiveSet& prims,
                                                       std::uint32_t active, const Ray* rays, const Real* t_min,
                                                       Real* t_max, std::uint32_t* prim, kernel::TriangleHit* hit) {
  static_assert(N == 8 || N == 16);
  using namespace wide_bvh_packet_detail;
  active &= (1u << N) - 1;
  PacketQuery<N> query(bvh, active, rays, t_min, t_max);
  PacketBoxes<N>& p = query.boxes;
  PacketTriangles<N>& q = query.triangles;
  const kernel::TriangleBlockRay* br = query.block_rays;
  std::uint32_t found = 0;
  auto leaf = [&](const WideBvhLeaf* first, std::uint32_t count, std::uint32_t lanes) -> std::uint32_t {
    query.prepare();
    std::uint32_t changed = 0;
#if defined(STRAHL_PACKET_AVX512)
    if (triangles_only(first, count)) {
      changed = leaf_triangles(first, count, q, lanes, false);
    } else
#elif defined(STRAHL_PACKET_AVX2)
    // Groups of three or four lanes with one axis order a triangle at a time; the rest lane by lane.
    if (triangles_only(first, count)) changed = leaf_triangles_dense(first, count, q, lanes);
#endif
    {
      for (std::uint32_t m = lanes; m != 0; m &= m - 1) {
        const int i = wide_bvh_detail::lowest_bit(m);
        Real t_far = q.t_far[i];
        kernel::TriangleHit h{q.t_far[i], q.b1[i], q.b2[i]};
        std::uint32_t pr = q.prim[i];
        kernel::blocks_nearest(first, count, prims, br[i], t_min[i], t_far, pr, h);
        if (t_far != q.t_far[i]) {
          q.t_far[i] = h.t;
          q.b1[i] = h.b1;
          q.b2[i] = h.b2;
          q.prim[i] = pr;
          changed |= 1u << i;
        }
      }
    }
    found |= changed;
    for (std::uint32_t m = changed; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      p.t_max[i] = wide_bvh_detail::round_up(q.t_far[i]);
    }
    if (changed != 0) lower_frustum(p, active);
    return 0;
  };
  traverse_packet<N, true>(bvh, p, active, leaf);
  for (std::uint32_t m = found; m != 0; m &= m - 1) {
    const int i = wide_bvh_detail::lowest_bit(m);
    t_max[i] = q.t_far[i];
    prim[i] = q.prim[i];
    hit[i] = kernel::TriangleHit{q.t_far[i], q.b1[i], q.b2[i]};
  }
}

// Which active lanes' rays hit something in (t_min[i], t_max[i]) (wide_bvh_occluded() on each):
// the mask of the occluded lanes.
template <int N>
STRAHL_HOST_DEVICE inline std::uint32_t wide_bvh_occluded_packet(const WideBvhView& bvh, const PrimitiveSet& prims,
                                                                 std::uint32_t active, const Ray* rays,
                                                                 const Real* t_min, const Real* t_max) {
  static_assert(N == 8 || N == 16);
  using namespace wide_bvh_packet_detail;
  active &= (1u << N) - 1;
  PacketQuery<N> query(bvh, active, rays, t_min, t_max);
  PacketBoxes<N>& p = query.boxes;
  [[maybe_unused]] PacketTriangles<N>& q = query.triangles;  // the AVX-512 leaves read it
  const kernel::TriangleBlockRay* br = query.block_rays;
  std::uint32_t occluded = 0;
  auto leaf = [&](const WideBvhLeaf* first, std::uint32_t count, std::uint32_t lanes) -> std::uint32_t {
    query.prepare();
    std::uint32_t done = 0;
#if defined(STRAHL_PACKET_AVX512)
    if (triangles_only(first, count)) {
      done = leaf_triangles(first, count, q, lanes, true);
    } else
#endif
    {
      for (std::uint32_t m = lanes; m != 0; m &= m - 1) {
        const int i = wide_bvh_detail::lowest_bit(m);
        if (kernel::blocks_any(first, count, prims, br[i], t_min[i], t_max[i])) done |= 1u << i;
      }
    }
    occluded |= done;
    return done;
  };
  traverse_packet<N, false>(bvh, p, active, leaf);
  return occluded;
}

}  // namespace strahl

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
