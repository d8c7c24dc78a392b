#include "strahl/accel/bvh.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#if defined(__AVX__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <memory>
#include <new>
#include <type_traits>

#include "strahl/accel/build_stats.h"
#include "strahl/util/large_array.h"

namespace strahl {

namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kParallelThreshold = 4096;  // subtrees smaller than this build on one thread
// Past this depth the build splits at the median, which at least halves every node: with at most
// 2^32 primitives the tree is then at most 64 deep, which the traversal stack relies on
// (bvh.h). SAH alone can peel off one primitive per level (geometrically spaced spheres).
constexpr std::size_t kMaxSahDepth = 32;

// A box as the build merges it: the low corner and the negated high corner in eight lanes
// (lo.x lo.y lo.z · −hi.x −hi.y −hi.z ·), so that merging two boxes is one minimum of eight
// doubles (one AVX-512 instruction, two AVX ones) — the very values of merge(): min and negation
// are exact, and `a < b ? a : b` picks as min()/max() do on equal values. A primitive's box
// carries its index in lane 3 (a double holds it exactly; the lane is never read as a bound), so
// the build moves one 64-byte record per primitive and every pass over a node's primitives reads
// one contiguous run, not the scene's boxes through an index.
struct alignas(64) BinBox {
  Real v[8] = {kInfinity, kInfinity, kInfinity, kInfinity, kInfinity, kInfinity, kInfinity, kInfinity};

  static BinBox of(const Bounds& b, std::uint32_t id) {
    BinBox r;
    r.v[0] = b.lo.x, r.v[1] = b.lo.y, r.v[2] = b.lo.z, r.v[3] = Real(id);
    r.v[4] = -b.hi.x, r.v[5] = -b.hi.y, r.v[6] = -b.hi.z, r.v[7] = 0;
    return r;
  }
  void merge(const BinBox& o) {
#if defined(__AVX512F__)
    // a < b ? a : b, lane by lane (the masked form: GCC 12 warns of _mm512_min_pd's undefined source)
    const __m512d a = _mm512_load_pd(v);
    _mm512_store_pd(v, _mm512_mask_min_pd(a, 0xff, a, _mm512_load_pd(o.v)));
#elif defined(__AVX__)
    _mm256_store_pd(v, _mm256_min_pd(_mm256_load_pd(v), _mm256_load_pd(o.v)));
    _mm256_store_pd(v + 4, _mm256_min_pd(_mm256_load_pd(v + 4), _mm256_load_pd(o.v + 4)));
#else
    for (int k = 0; k < 8; ++k) v[k] = v[k] < o.v[k] ? v[k] : o.v[k];
#endif
  }
  Bounds bounds() const { return Bounds{Vec3(v[0], v[1], v[2]), Vec3(-v[4], -v[5], -v[6])}; }
  // (lo + hi) / 2, as (lo − (−hi)) / 2: the same IEEE operation.
  Vec3 centroid() const { return Vec3(v[0] - v[4], v[1] - v[5], v[2] - v[6]) * Real(0.5); }
  std::uint32_t id() const { return std::uint32_t(v[3]); }
};
using PrimRef = BinBox;

// Builds into a node array sized for the worst case (2n − 1 nodes): a split takes the next two
// free slots for its children, so subtrees build in parallel without a temporary tree. The array
// is allocated, not initialised (in 2 MiB pages when large: util/large_array.h): each node is
// constructed when its build begins, so the memory past the nodes taken (a prefix: slots are
// handed out in order; about n/2 of the 2n − 1 for triangle meshes) is never touched and costs
// neither time nor resident memory.
struct Builder {
  PrimRef* refs;
  BvhNode* nodes;
  const BvhBuildOptions& options;
  // Primitives from this index on are solids (accel/primitive.h puts them last): each costs a
  // test of its own (a cone's quadratic, a torus's quartic, an implicit surface's search), not
  // a share of a block test, so the SAH does not pack them into one leaf behind one box.
  std::uint32_t first_costly = ~std::uint32_t(0);
  std::atomic<std::uint32_t> next_node{1};
  // The tree's leaves and depth (the root's is 1), counted as the leaves are made.
  std::atomic<std::size_t> leaves{0}, max_depth{0};

  // SAH cost of a leaf of n primitives of which `costly` are solids, in primitive (block) tests.
  Real leaf_cost(std::uint32_t n, std::uint32_t costly = 0) const {
    return Real((n - costly + options.leaf_block - 1) / options.leaf_block + costly);
  }

  void build(std::uint32_t at, std::uint32_t begin, std::uint32_t end, std::size_t depth) {
    BinBox box;
    Bounds centroid_bounds;
    for (std::uint32_t i = begin; i < end; ++i) {
      box.merge(refs[i]);
      centroid_bounds.extend(refs[i].centroid());
    }
    const Bounds bounds = box.bounds();
    BvhNode& node = *::new (static_cast<void*>(nodes + at)) BvhNode{};
    node.bounds = bounds;
    const std::uint32_t count = end - begin;
    std::uint32_t costly = 0;
    if (first_costly != ~std::uint32_t(0))
      for (std::uint32_t i = begin; i < end; ++i) costly += refs[i].id() >= first_costly;
    const auto make_leaf = [&] {
      node.offset = begin;
      node.count = std::uint16_t(count);
      leaves.fetch_add(1, std::memory_order_relaxed);
      std::size_t deepest = max_depth.load(std::memory_order_relaxed);
      while (depth > deepest && !max_depth.compare_exchange_weak(deepest, depth, std::memory_order_relaxed)) {
      }
    };
    // Tiny scenes (the lecture's five spheres) are one leaf: see traverse(). Not when they hold
    // solids, whose own tests cost more than a box test.
    const std::uint32_t max_leaf = options.max_leaf;
    if (count <= 1 || (costly == 0 && (count <= 2 || (at == 0 && count <= max_leaf)))) return make_leaf();

    // Binned SAH: the best of kBins − 1 candidate planes on each axis, all axes in one pass.
    std::array<std::array<BinBox, kBins>, 3> bin_bounds;
    std::array<std::array<std::uint32_t, kBins>, 3> bin_count{}, bin_costly{};
    Vec3 scale;
    for (int axis = 0; axis < 3; ++axis) {
      const Real extent = centroid_bounds.hi[axis] - centroid_bounds.lo[axis];
      (axis == 0 ? scale.x : axis == 1 ? scale.y : scale.z) = extent > 0 ? kBins / extent : 0;
    }
    const auto bin_of = [&](const Vec3& c, int axis) {
      return std::min(kBins - 1, int((c[axis] - centroid_bounds.lo[axis]) * scale[axis]));
    };
    const auto bin_all = [&](auto with_costly) {
      for (std::uint32_t i = begin; i < end; ++i) {
        const PrimRef& p = refs[i];
        const Vec3 c = p.centroid();
        for (int axis = 0; axis < 3; ++axis) {
          const int b = bin_of(c, axis);
          bin_bounds[axis][b].merge(p);
          ++bin_count[axis][b];
          if constexpr (decltype(with_costly)::value) bin_costly[axis][b] += p.id() >= first_costly;
        }
      }
    };
    if (costly > 0) bin_all(std::true_type{});
    else bin_all(std::false_type{});
    // The candidate planes between two bins that hold primitives all split alike (the empty bins
    // between them add nothing to either side), so only the bins in use are swept: a small node
    // uses a few of the kBins. Of equal costs the first plane wins, as in a sweep over every bin:
    // the plane right after a bin in use.
    Real best_cost = kInfinity;
    int best_axis = -1, best_split = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (scale[axis] == 0) continue;
      std::array<int, kBins> used;
      int m = 0;
      for (int b = 0; b < kBins; ++b)
        if (bin_count[axis][b] > 0) used[m++] = b;
      std::array<Real, kBins> right_area;
      std::array<std::uint32_t, kBins> right_count, right_costly;
      Bounds acc;
      std::uint32_t n = 0, nc = 0;
      for (int j = m - 1; j > 0; --j) {
        acc = merge(acc, bin_bounds[axis][used[j]].bounds());
        n += bin_count[axis][used[j]];
        nc += bin_costly[axis][used[j]];
        right_area[j] = surface_area(acc);
        right_count[j] = n;
        right_costly[j] = nc;
      }
      acc = Bounds{};
      n = nc = 0;
      for (int j = 0; j < m - 1; ++j) {
        acc = merge(acc, bin_bounds[axis][used[j]].bounds());
        n += bin_count[axis][used[j]];
        nc += bin_costly[axis][used[j]];
        const Real cost = surface_area(acc) * leaf_cost(n, nc) +
                          right_area[j + 1] * leaf_cost(right_count[j + 1], right_costly[j + 1]);
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_split = used[j] + 1;
        }
      }
    }
    const Real area = surface_area(bounds);
    const Real split_cost = area > 0 ? Real(options.traversal_cost) + best_cost / area : kInfinity;
    // A leaf when splitting does not pay and the leaf stays small. Coinciding centroids (no SAH
    // split) are split in halves below, so leaves never exceed max_leaf.
    if (count <= max_leaf && (best_axis < 0 || leaf_cost(count, costly) <= split_cost)) return make_leaf();

    std::uint32_t mid = begin + count / 2;
    std::uint8_t axis = 0;
    if (depth >= kMaxSahDepth || best_axis < 0) {
      // Median split on the widest centroid axis (all centroids may coincide: then any halves).
      const Vec3 extent = centroid_bounds.hi - centroid_bounds.lo;
      axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
      std::nth_element(refs + begin, refs + mid, refs + end,
                       [&](const PrimRef& a, const PrimRef& b) { return a.centroid()[axis] < b.centroid()[axis]; });
    } else {
      axis = std::uint8_t(best_axis);
      PrimRef* split = std::partition(refs + begin, refs + end,
                                      [&](const PrimRef& p) { return bin_of(p.centroid(), best_axis) < best_split; });
      mid = std::uint32_t(split - refs);
      if (mid == begin || mid == end) mid = begin + count / 2;
    }
    const std::uint32_t children = next_node.fetch_add(2);
    node.offset = children;
    node.count = 0;
    node.axis = axis;
    if (count > kParallelThreshold) {
      tbb::parallel_invoke([&] { build(children, begin, mid, depth + 1); },
                           [&] { build(children + 1, mid, end, depth + 1); });
    } else {
      build(children, begin, mid, depth + 1);
      build(children + 1, mid, end, depth + 1);
    }
  }
};

// Gives the node slots back (util/large_array.h: how they were allocated depends on their size).
struct SlotsDeleter {
  std::size_t count;
  void operator()(BvhNode* p) const { LargeArrayAllocator<BvhNode>().deallocate(p, count); }
};

// The build over n boxes; `start` is when the caller began (the boxes' time counts).
Bvh build_bvh(const Bounds* bounds, std::uint32_t n, AccelBuildStats* stats_out, const BvhBuildOptions& options,
              std::uint32_t first_costly, std::chrono::steady_clock::time_point start) {
  Bvh bvh;
  AccelBuildStats stats;
  stats.primitives = stats.primitive_references = n;
  if (n > 0) {
    LargeArray<PrimRef> refs(n);
    bvh.prims.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, n, 1024), [&](const auto& r) {
      for (std::uint32_t i = r.begin(); i != r.end(); ++i) refs[i] = BinBox::of(bounds[i], i);
    });
    static_assert(std::is_trivially_copyable_v<BvhNode> && std::is_trivially_destructible_v<BvhNode>);
    const std::size_t slot_count = 2 * std::size_t(n) - 1;
    const std::unique_ptr<BvhNode, SlotsDeleter> slots(LargeArrayAllocator<BvhNode>().allocate(slot_count),
                                                      SlotsDeleter{slot_count});
    Builder builder{refs.data(), slots.get(), options, first_costly};
    builder.build(0, 0, n, 1);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, n, 1024), [&](const auto& r) {
      for (std::uint32_t i = r.begin(); i != r.end(); ++i) bvh.prims[i] = refs[i].id();
    });
    bvh.nodes.assign(slots.get(), slots.get() + builder.next_node.load());
    stats.leaves = builder.leaves.load();
    stats.max_depth = builder.max_depth.load();
  }
  stats.nodes = bvh.nodes.size();
  stats.bytes = bvh.nodes.size() * sizeof(BvhNode) + bvh.prims.size() * sizeof(std::uint32_t);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats_out) *stats_out = stats;
  return bvh;
}

}  // namespace

Bvh build_bvh(const std::vector<Bounds>& bounds, AccelBuildStats* stats_out, const BvhBuildOptions& options,
              std::uint32_t first_costly) {
  return build_bvh(bounds.data(), static_cast<std::uint32_t>(bounds.size()), stats_out, options, first_costly,
                   std::chrono::steady_clock::now());
}

Bvh build_bvh(const PrimitiveSet& prims, AccelBuildStats* stats_out, const BvhBuildOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  LargeArray<Bounds> bounds(prims.size());
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, prims.size(), 1024), [&](const auto& r) {
    for (std::uint32_t i = r.begin(); i != r.end(); ++i) bounds[i] = primitive_bounds(prims, i);
  });
  return build_bvh(bounds.data(), prims.size(), stats_out, options, prims.first_solid(), start);
}

}  // namespace strahl
