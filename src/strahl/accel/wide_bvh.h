#pragma once
// The BVH the renderer uses (--accel bvh): the binary SAH BVH of bvh.h collapsed into an 8-wide
// one, as Embree does on AVX2 machines. Each node holds the boxes of its (up to) eight children
// side by side in float (structure of arrays, rounded outward so no box shrinks), and one AVX slab
// test checks a ray against all eight at once (8-wide measured ~10-15% more incoherent and shadow
// rays per second than 4-wide with SSE on the dragon and the bunny; without AVX2 a scalar loop
// does the same test); the children hit are visited nearest first and the traversal stops at a
// hit nearer than every box still waiting (occlusion: in slot order, up to the first hit — 6-11 %
// more shadow rays per second on the meshes than sorted). Leaves hold contiguous copies of their
// triangles' vertices in blocks of four (accel/triangle_block.h: no indirection through primitive
// indices in the hot loop), tested four at once in double with the watertight test of
// geometry/triangle.h, bit for bit as the scalar test.
//
// The float slab test is made conservative: per ray and axis, t = box·(1/d) + (−o/d) is computed
// with a margin covering every rounding of the float arithmetic (and of o and 1/d converted to
// float), so a box the exact test would meet within (t_min, t_max) is never culled. An axis whose
// direction component is zero (or whose figures overflow float) culls nothing. The answers are
// therefore exactly those of the naive loop, which the cross-check tests demand.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "strahl/accel/primitive.h"
#include "strahl/accel/traversal.h"
#include "strahl/accel/triangle_block.h"
#include "strahl/util/large_array.h"

// STRAHL_PORTABLE_KERNELS: the portable path (what the GPU runs) on an AVX2 host too
// (tests/portable checks the two give the same hits, bit for bit).
#if !defined(__CUDACC__) && defined(__AVX2__) && !defined(STRAHL_PORTABLE_KERNELS)
#include <immintrin.h>
#define STRAHL_WIDE_BVH_AVX 1
#endif

namespace strahl {

inline constexpr int kWideBvhWidth = 8;
inline constexpr std::uint32_t kWideBvhEmpty = ~std::uint32_t(0);

struct alignas(64) WideBvhNode {
  float lo[3][kWideBvhWidth];  // [axis][child]; an empty slot has lo = +∞, hi = −∞
  float hi[3][kWideBvhWidth];
  std::uint32_t child[kWideBvhWidth];  // inner child: its node index; leaf: its first block;
                                       // empty slot: kWideBvhEmpty
  std::uint32_t count[kWideBvhWidth];  // leaf: number of blocks (≥ 1); inner child or empty: 0
};
static_assert(sizeof(WideBvhNode) == 256);

// A leaf is a run of triangle blocks (accel/triangle_block.h: four triangles' vertices copied side
// by side, tested four at once); its spheres and solids sit in lanes of their own (the `other` bits)
// and are tested from the primitive set's arrays: they are few where speed matters.
using WideBvhLeaf = kernel::TriangleBlock;

// A wide tree's arrays. A leaf is a run of `LeafEntry`s: triangle blocks in the scene's BVH,
// indices in the instances' and the moving shapes' trees (IndexTree below), all traversed alike.
template <class LeafEntry>
struct WideBvhViewOf {
  const WideBvhNode* nodes = nullptr;
  const LeafEntry* leaves = nullptr;
  std::uint32_t root_leaf_count = 0;  // > 0: the whole tree is one leaf of this many entries (no nodes)
  float extent[3] = {0, 0, 0};        // the largest |coordinate| of any box, per axis (for the margins)
};
using WideBvhView = WideBvhViewOf<WideBvhLeaf>;

// Owns the arrays (nodes aligned to 64 bytes, a cache line; large ones in 2 MiB pages).
struct WideBvh {
  LargeArray<WideBvhNode> nodes;
  LargeArray<WideBvhLeaf> leaves;
  std::uint32_t root_leaf_count = 0;
  float extent[3] = {0, 0, 0};
  WideBvhView view() const {
    return {nodes.empty() ? nullptr : nodes.data(), leaves.empty() ? nullptr : leaves.data(), root_leaf_count,
            {extent[0], extent[1], extent[2]}};
  }
};

struct AccelBuildStats;
WideBvh build_wide_bvh(const PrimitiveSet& prims, AccelBuildStats* stats = nullptr);

// A wide tree whose leaves are runs of indices into the caller's arrays: the instances' tree
// (render/instance_queries.h) and the moving shapes' trees (accel/motion_bvh.h).
using IndexTreeView = WideBvhViewOf<std::uint32_t>;

struct IndexTree {
  LargeArray<WideBvhNode> nodes;
  std::vector<std::uint32_t> prims;  // the leaves' entries
  std::uint32_t root_leaf_count = 0;
  float extent[3] = {0, 0, 0};
  IndexTreeView view() const {
    return {nodes.empty() ? nullptr : nodes.data(), prims.empty() ? nullptr : prims.data(), root_leaf_count,
            {extent[0], extent[1], extent[2]}};
  }
};

// The binary SAH tree over `boxes` (bvh.h) collapsed into a wide one: its leaves' entries are
// indices into `boxes`; one leaf (a few boxes) stays a root leaf, without nodes.
IndexTree build_index_tree(const std::vector<Bounds>& boxes);

// Raises extent (per axis, the largest |coordinate| of any box: the margins of the float box
// test) to cover `box`.
void widen_extent(float extent[3], const Bounds& box);

// Appends to `out` the wide nodes of a binary tree (bvh.h's layout, `binary[0]` an inner root),
// collapsed as build_wide_bvh collapses it, its root first; returns the root's index in `out`.
// Inner children's indices count from the root (a view of the tree starts there). A binary leaf
// stays a leaf: child = its offset into the binary tree's primitive order, count = its number
// of primitives.
struct BvhNode;
std::uint32_t append_wide_nodes(const BvhNode* binary, LargeArray<WideBvhNode>& out);

// Appends a wide root whose one child is the leaf of `count` primitives from offset 0 in `box`
// (a tree that is one leaf, when its box test pays: the primitives cost more than it); returns
// its index in `out`.
std::uint32_t append_wide_leaf_root(const Bounds& box, std::uint32_t count, LargeArray<WideBvhNode>& out);

namespace wide_bvh_detail {

// The float nearest x from below / above.
STRAHL_HOST_DEVICE inline float round_down(Real x) {
  float f = float(x);
  if (Real(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
STRAHL_HOST_DEVICE inline float round_up(Real x) {
  float f = float(x);
  if (Real(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// Per ray: t_entry(axis) = near·inv + near_offset, t_exit(axis) = far·inv + far_offset, where
// near/far are the box's lo/hi by the sign of the direction.
struct RayBoxes {
  float inv[3];
  float near_offset[3], far_offset[3];
  int negative[3];
};

template <class LeafEntry>
STRAHL_HOST_DEVICE inline RayBoxes ray_boxes(const WideBvhViewOf<LeafEntry>& bvh, const Ray& ray) {
  RayBoxes r;
  const Real o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  const Real d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  for (int a = 0; a < 3; ++a) {
    const Real inv = Real(1) / d[a];
    // Every rounding of the float evaluation of (x − o)·inv for |x| ≤ extent is below
    // 4·2⁻²⁴·(|x| + |o|)·|inv|; the margin is twice that.
    const Real margin = (Real(bvh.extent[a]) + std::fabs(o[a])) * std::fabs(inv) * 0x1p-21;
    const float inv_f = float(inv), offset = float(-o[a] * inv), margin_f = float(margin);
    r.negative[a] = std::signbit(d[a]) ? 1 : 0;
    if (std::isfinite(inv_f) && std::isfinite(offset) && std::isfinite(margin_f) && std::isfinite(offset + margin_f) &&
        std::isfinite(offset - margin_f)) {
      r.inv[a] = inv_f;
      r.near_offset[a] = offset - margin_f;
      r.far_offset[a] = offset + margin_f;
    } else {  // parallel to the axis (or beyond float): no constraint from this axis
      r.inv[a] = 0;
      r.near_offset[a] = -std::numeric_limits<float>::infinity();
      r.far_offset[a] = std::numeric_limits<float>::infinity();
    }
  }
  return r;
}

// The lowest set bit's index (m ≠ 0).
STRAHL_HOST_DEVICE inline int lowest_bit(unsigned m) {
#if defined(__CUDA_ARCH__)
  return __ffs(int(m)) - 1;
#else
  return __builtin_ctz(m);
#endif
}

// The number of bits set in m.
STRAHL_HOST_DEVICE inline int popcount(unsigned m) {
#if defined(__CUDA_ARCH__)
  return __popc(m);
#else
  return __builtin_popcount(m);
#endif
}

struct StackEntry {
  std::uint32_t child, count;
  float t_near;
};

}  // namespace wide_bvh_detail

// Calls leaf(first, count, t_max) for the entries of every leaf whose box the ray meets within
// (t_min, t_max); leaf returns true to stop at once. kOrdered: the children met nearest first, and
// leaf may lower t_max (a waiting box beyond it is then skipped) — nearest-hit queries; else in
// slot order, none skipped, and leaf leaves t_max as it is — queries that stop at their first hit
// (occlusion: the distances would decide nothing; as the packets' traversal, wide_bvh_packet.h).
template <bool kOrdered = true, class LeafEntry, class Leaf>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void traverse_leaves(const WideBvhViewOf<LeafEntry>& bvh, const Ray& ray,
                                                           Real t_min, Real& t_max, Leaf& leaf) {
  using namespace wide_bvh_detail;
  if (bvh.root_leaf_count > 0) {
    leaf(bvh.leaves, bvh.root_leaf_count, t_max);
    return;
  }
  if (bvh.nodes == nullptr) return;
  const RayBoxes rb = ray_boxes(bvh, ray);
  const float t_min_f = round_down(t_min);
  float t_max_f = round_up(t_max);
  // A binary tree at most 64 deep (bvh.cpp) collapses into at most 64 levels, each leaving at
  // most kWideBvhWidth − 1 siblings waiting.
  StackEntry stack[(kWideBvhWidth - 1) * 64 + 4];
  int top = 0;
  std::uint32_t child = 0, count = 0;  // the root node
#if defined(STRAHL_WIDE_BVH_AVX)
  static_assert(kWideBvhWidth == 8);
  const __m256 inv_x = _mm256_set1_ps(rb.inv[0]), inv_y = _mm256_set1_ps(rb.inv[1]), inv_z = _mm256_set1_ps(rb.inv[2]);
  const __m256 no_x = _mm256_set1_ps(rb.near_offset[0]), no_y = _mm256_set1_ps(rb.near_offset[1]),
               no_z = _mm256_set1_ps(rb.near_offset[2]);
  const __m256 fo_x = _mm256_set1_ps(rb.far_offset[0]), fo_y = _mm256_set1_ps(rb.far_offset[1]),
               fo_z = _mm256_set1_ps(rb.far_offset[2]);
  // Byte offsets of the near and far planes of each axis within a node (lo at 0, hi at 96).
  const std::size_t near_x = rb.negative[0] ? 96 : 0, far_x = rb.negative[0] ? 0 : 96;
  const std::size_t near_y = 32 + (rb.negative[1] ? 96 : 0), far_y = 32 + (rb.negative[1] ? 0 : 96);
  const std::size_t near_z = 64 + (rb.negative[2] ? 96 : 0), far_z = 64 + (rb.negative[2] ? 0 : 96);
  const __m256 t_min_v = _mm256_set1_ps(t_min_f);
  __m256 t_max_v = _mm256_set1_ps(t_max_f);
#endif
  for (;;) {
    if (count == 0) {
      const WideBvhNode& n = bvh.nodes[child];
      alignas(32) float t_near[kWideBvhWidth];
      int mask = 0;
#if defined(STRAHL_WIDE_BVH_AVX)
      const char* base = reinterpret_cast<const char*>(&n);
      const auto plane = [&](std::size_t offset) {
        return _mm256_load_ps(reinterpret_cast<const float*>(base + offset));
      };
      // max/min return their second operand when either is NaN: the accumulated bound comes
      // second, so a NaN from one axis (0·∞) constrains nothing.
      const __m256 tn_x = _mm256_add_ps(_mm256_mul_ps(plane(near_x), inv_x), no_x);
      const __m256 tn_y = _mm256_add_ps(_mm256_mul_ps(plane(near_y), inv_y), no_y);
      const __m256 tn_z = _mm256_add_ps(_mm256_mul_ps(plane(near_z), inv_z), no_z);
      const __m256 tf_x = _mm256_add_ps(_mm256_mul_ps(plane(far_x), inv_x), fo_x);
      const __m256 tf_y = _mm256_add_ps(_mm256_mul_ps(plane(far_y), inv_y), fo_y);
      const __m256 tf_z = _mm256_add_ps(_mm256_mul_ps(plane(far_z), inv_z), fo_z);
      const __m256 tn = _mm256_max_ps(tn_x, _mm256_max_ps(tn_y, _mm256_max_ps(tn_z, t_min_v)));
      const __m256 tf = _mm256_min_ps(tf_x, _mm256_min_ps(tf_y, _mm256_min_ps(tf_z, t_max_v)));
      mask = _mm256_movemask_ps(_mm256_cmp_ps(tn, tf, _CMP_LE_OQ));
      if constexpr (kOrdered) _mm256_store_ps(t_near, tn);
#else
      for (int k = 0; k < kWideBvhWidth; ++k) {
        float lo = t_min_f, hi = t_max_f;
        for (int a = 0; a < 3; ++a) {
          const float near = rb.negative[a] ? n.hi[a][k] : n.lo[a][k];
          const float far = rb.negative[a] ? n.lo[a][k] : n.hi[a][k];
          const float t0 = near * rb.inv[a] + rb.near_offset[a], t1 = far * rb.inv[a] + rb.far_offset[a];
          lo = t0 > lo ? t0 : lo;  // NaN keeps the bound
          hi = t1 < hi ? t1 : hi;
        }
        t_near[k] = lo;
        if (lo <= hi) mask |= 1 << k;
      }
#endif
      // The children hit, nearest first (equal entries in slot order). An empty slot's box is
      // inverted, but on a ray whose every axis is unconstrained (coordinates beyond float) it
      // would pass: skip it.
#if defined(STRAHL_WIDE_BVH_AVX)
      mask &= ~_mm256_movemask_ps(_mm256_castsi256_ps(
          _mm256_cmpeq_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(n.child)), _mm256_set1_epi32(-1))));
#else
      for (int k = 0; k < kWideBvhWidth; ++k)
        if (n.child[k] == kWideBvhEmpty) mask &= ~(1 << k);
#endif
      if constexpr (!kOrdered) {
        if (mask != 0) {
          const int k0 = lowest_bit(unsigned(mask));
          for (unsigned rest = unsigned(mask) & unsigned(mask - 1); rest != 0; rest &= rest - 1) {
            const int k = lowest_bit(rest);
            stack[top++] = {n.child[k], n.count[k], 0.0f};
          }
          child = n.child[k0];
          count = n.count[k0];
          continue;
        }
      } else if (mask != 0) {
        int k0 = lowest_bit(unsigned(mask));
        mask &= mask - 1;
        if (mask != 0) {
          int k1 = lowest_bit(unsigned(mask));
          mask &= mask - 1;
          if (mask == 0) {  // two: the common case after one
            if (t_near[k1] < t_near[k0]) { const int tmp = k0; k0 = k1; k1 = tmp; }
            stack[top++] = {n.child[k1], n.count[k1], t_near[k1]};
          } else {  // three or more: insertion sort
            int order[kWideBvhWidth] = {k0, k1}, hits = 2;
            if (t_near[k1] < t_near[k0]) { order[0] = k1; order[1] = k0; }
            while (mask != 0) {
              const int k = lowest_bit(unsigned(mask));
              mask &= mask - 1;
              int j = hits++;
              for (; j > 0 && t_near[order[j - 1]] > t_near[k]; --j) order[j] = order[j - 1];
              order[j] = k;
            }
            for (int i = hits - 1; i > 0; --i) stack[top++] = {n.child[order[i]], n.count[order[i]], t_near[order[i]]};
            k0 = order[0];
          }
        }
        child = n.child[k0];
        count = n.count[k0];
        continue;
      }
    } else if constexpr (!kOrdered) {
      if (leaf(bvh.leaves + child, count, t_max)) return;
    } else {
      const Real before = t_max;
      if (leaf(bvh.leaves + child, count, t_max)) return;
      if (t_max != before) {
        t_max_f = round_up(t_max);
#if defined(STRAHL_WIDE_BVH_AVX)
        t_max_v = _mm256_set1_ps(t_max_f);
#endif
      }
    }
    if constexpr (!kOrdered) {  // the next waiting box, whatever its distance
      if (top == 0) return;
      --top;
      child = stack[top].child;
      count = stack[top].count;
    } else {  // the next waiting box that still begins before the nearest hit found
      for (;;) {
        if (top == 0) return;
        const StackEntry& e = stack[--top];
        if (e.t_near <= t_max_f) {
          child = e.child;
          count = e.count;
          break;
        }
      }
    }
  }
}

// The visitor traversal of traversal.h (for queries other than nearest hit and occlusion).
template <class Visitor>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void traverse(const WideBvhView& bvh, const Ray& ray, Real t_min, Real& t_max,
                                                     Visitor& visit) {
  auto leaf = [&](const WideBvhLeaf* first, std::uint32_t count, Real& t_far) {
    for (std::uint32_t i = 0; i < count; ++i)
      for (int k = 0; k < kernel::kTriangleBlockWidth; ++k)
        if (first[i].prim[k] != kernel::kTriangleBlockEmpty && visit(first[i].prim[k], -kInfinity, kInfinity, t_far))
          return true;
    return false;
  };
  traverse_leaves(bvh, ray, t_min, t_max, leaf);
}

// The visitor traversal over an index tree: visitor(index, −∞, ∞, t_max) for the entries of every
// leaf the ray reaches; kNearestFirst: nearer boxes first, and the visitor may lower t_max; else
// in slot order (queries that stop at their first hit).
template <bool kNearestFirst = true, class Visitor>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void traverse(const IndexTreeView& tree, const Ray& ray, Real t_min, Real& t_max,
                                                     Visitor& visit) {
  auto leaf = [&](const std::uint32_t* first, std::uint32_t count, Real& t_far) {
    for (std::uint32_t i = 0; i < count; ++i)
      if (visit(first[i], -kInfinity, kInfinity, t_far)) return true;
    return false;
  };
  traverse_leaves<kNearestFirst>(tree, ray, t_min, t_max, leaf);
}

// The nearest hit in (t_min, t_max) among the leaves' primitives: its id and hit, t = kInfinity
// when none.
STRAHL_HOST_DEVICE inline void wide_bvh_nearest(const WideBvhView& bvh, const PrimitiveSet& prims, const Ray& ray,
                                                Real t_min, Real t_max, std::uint32_t& prim, kernel::TriangleHit& hit) {
  const kernel::TriangleBlockRay br = kernel::triangle_block_ray(ray, ray_shear_for(prims, ray.direction));
  auto leaf = [&](const WideBvhLeaf* first, std::uint32_t count, Real& t_far) {
    kernel::blocks_nearest(first, count, prims, br, t_min, t_far, prim, hit);
    return false;
  };
  traverse_leaves(bvh, ray, t_min, t_max, leaf);
}

// Any hit in (t_min, t_max)? Stops at the first one.
STRAHL_HOST_DEVICE inline bool wide_bvh_occluded(const WideBvhView& bvh, const PrimitiveSet& prims, const Ray& ray,
                                                 Real t_min, Real t_max) {
  const kernel::TriangleBlockRay br = kernel::triangle_block_ray(ray, ray_shear_for(prims, ray.direction));
  bool found = false;
  auto leaf = [&](const WideBvhLeaf* first, std::uint32_t count, const Real& t_far) {
    return found = kernel::blocks_any(first, count, prims, br, t_min, t_far);
  };
  traverse_leaves<false>(bvh, ray, t_min, t_max, leaf);
  return found;
}

}  // namespace strahl
