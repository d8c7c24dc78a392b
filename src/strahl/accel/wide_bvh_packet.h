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

#include "strahl/accel/packet_boxes.h"
#include "strahl/accel/packet_leaves.h"
#include "strahl/accel/packet_simd.h"
#include "strahl/accel/primitive.h"
#include "strahl/accel/triangle_block.h"
#include "strahl/accel/wide_bvh.h"

STRAHL_PACKET_WARNINGS_OFF

namespace strahl {
namespace wide_bvh_packet_detail {

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

STRAHL_PACKET_WARNINGS_ON
