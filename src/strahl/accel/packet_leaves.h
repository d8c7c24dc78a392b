#pragma once
// The leaves of the packet traversal (wide_bvh_packet.h): one triangle against the packet's rays at
// once (AVX-512 / AVX2, double).
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

#include <cstdint>

#include "strahl/accel/packet_simd.h"
#include "strahl/accel/triangle_block.h"
#include "strahl/accel/wide_bvh.h"

STRAHL_PACKET_WARNINGS_OFF

namespace strahl::wide_bvh_packet_detail {

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

}  // namespace strahl::wide_bvh_packet_detail

STRAHL_PACKET_WARNINGS_ON
