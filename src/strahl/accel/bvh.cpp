#include "strahl/accel/bvh.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <memory>

#include "strahl/accel/build_stats.h"

namespace strahl {

namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeafSize = 8;
constexpr std::uint32_t kParallelThreshold = 4096;
// Past this depth the build splits at the median, which at least halves every node: with at most
// 2^32 primitives the tree is then at most 64 deep, which the traversal stack relies on
// (bvh.h). SAH alone can peel off one primitive per level (geometrically spaced spheres).
constexpr std::size_t kMaxSahDepth = 32;  // subtrees smaller than this build on one thread
// SAH costs relative to one primitive test.
constexpr Real kTraversalCost = 1.0;

Real surface_area(const Bounds& b) {
  if (b.empty()) return 0;
  const Vec3 d = b.hi - b.lo;
  return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

Bounds merge(const Bounds& a, const Bounds& b) {
  Bounds r;
  r.lo = min(a.lo, b.lo);
  r.hi = max(a.hi, b.hi);
  return r;
}

struct BuildNode {
  Bounds bounds;
  std::uint32_t first = 0, count = 0;  // range in the primitive index array (leaves)
  std::uint8_t axis = 0;
  std::unique_ptr<BuildNode> left, right;
};

struct Builder {
  const std::vector<Bounds>& prim_bounds;
  const std::vector<Vec3>& centroids;
  std::vector<std::uint32_t>& index;

  std::unique_ptr<BuildNode> build(std::uint32_t begin, std::uint32_t end, std::size_t depth) {
    auto node = std::make_unique<BuildNode>();
    Bounds bounds, centroid_bounds;
    for (std::uint32_t i = begin; i < end; ++i) {
      bounds = merge(bounds, prim_bounds[index[i]]);
      centroid_bounds.extend(centroids[index[i]]);
    }
    node->bounds = bounds;
    const std::uint32_t count = end - begin;
    const auto make_leaf = [&] {
      node->first = begin;
      node->count = count;
      return std::move(node);
    };
    // Tiny scenes (the lecture's five spheres) are one leaf: see traverse().
    if (count <= 2 || (begin == 0 && end == index.size() && count <= kMaxLeafSize)) return make_leaf();

    // Binned SAH: the best of kBins − 1 candidate planes on each axis.
    Real best_cost = kInfinity;
    int best_axis = -1, best_split = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const Real lo = centroid_bounds.lo[axis], extent = centroid_bounds.hi[axis] - lo;
      if (!(extent > 0)) continue;
      std::array<Bounds, kBins> bin_bounds;
      std::array<std::uint32_t, kBins> bin_count{};
      const Real scale = kBins / extent;
      for (std::uint32_t i = begin; i < end; ++i) {
        const int b = std::min(kBins - 1, int((centroids[index[i]][axis] - lo) * scale));
        bin_bounds[b] = merge(bin_bounds[b], prim_bounds[index[i]]);
        ++bin_count[b];
      }
      std::array<Real, kBins> right_area{};
      std::array<std::uint32_t, kBins> right_count{};
      Bounds acc;
      std::uint32_t n = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc = merge(acc, bin_bounds[b]);
        n += bin_count[b];
        right_area[b] = surface_area(acc);
        right_count[b] = n;
      }
      acc = Bounds{};
      n = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        acc = merge(acc, bin_bounds[b]);
        n += bin_count[b];
        const Real cost = surface_area(acc) * n + right_area[b + 1] * right_count[b + 1];
        if (n > 0 && right_count[b + 1] > 0 && cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_split = b + 1;
        }
      }
    }
    const Real leaf_cost = Real(count);
    const Real area = surface_area(bounds);
    const Real split_cost = area > 0 ? kTraversalCost + best_cost / area : kInfinity;
    // A leaf when splitting does not pay and the leaf stays small. Coinciding centroids (no SAH
    // split) are split in halves below, so leaves never exceed kMaxLeafSize.
    if (count <= kMaxLeafSize && (best_axis < 0 || leaf_cost <= split_cost)) return make_leaf();

    std::uint32_t mid;
    if (depth >= kMaxSahDepth) {
      // Median split on the widest centroid axis.
      const Vec3 extent = centroid_bounds.empty() ? Vec3(0) : centroid_bounds.hi - centroid_bounds.lo;
      const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
      mid = begin + count / 2;
      std::nth_element(index.data() + begin, index.data() + mid, index.data() + end,
                       [&](std::uint32_t a, std::uint32_t b) { return centroids[a][axis] < centroids[b][axis]; });
      node->axis = std::uint8_t(axis);
    } else if (best_axis >= 0) {
      const Real lo = centroid_bounds.lo[best_axis];
      const Real scale = kBins / (centroid_bounds.hi[best_axis] - lo);
      auto* split = std::partition(index.data() + begin, index.data() + end, [&](std::uint32_t p) {
        return std::min(kBins - 1, int((centroids[p][best_axis] - lo) * scale)) < best_split;
      });
      mid = std::uint32_t(split - index.data());
      node->axis = std::uint8_t(best_axis);
    } else {
      // All centroids coincide (e.g. duplicated primitives): split the list in half.
      mid = begin + count / 2;
      node->axis = 0;
    }
    if (mid == begin || mid == end) mid = begin + count / 2;
    if (count > kParallelThreshold) {
      tbb::parallel_invoke([&] { node->left = build(begin, mid, depth + 1); },
                           [&] { node->right = build(mid, end, depth + 1); });
    } else {
      node->left = build(begin, mid, depth + 1);
      node->right = build(mid, end, depth + 1);
    }
    return node;
  }
};

void flatten(const BuildNode& n, std::vector<BvhNode>& out, std::size_t depth, AccelBuildStats& stats) {
  stats.max_depth = std::max(stats.max_depth, depth);
  const std::size_t at = out.size();
  out.push_back({n.bounds, n.first, std::uint16_t(n.left ? 0 : n.count), n.axis});
  if (!n.left) {
    ++stats.leaves;
    return;
  }
  flatten(*n.left, out, depth + 1, stats);
  out[at].offset = std::uint32_t(out.size());
  flatten(*n.right, out, depth + 1, stats);
}

}  // namespace

Bvh build_bvh(const PrimitiveSet& prims, AccelBuildStats* stats_out) {
  const auto start = std::chrono::steady_clock::now();
  const std::uint32_t n = prims.size();
  Bvh bvh;
  AccelBuildStats stats;
  stats.primitives = stats.primitive_references = n;
  if (n > 0) {
    std::vector<Bounds> bounds(n);
    std::vector<Vec3> centroids(n);
    bvh.prims.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, n, 1024), [&](const auto& r) {
      for (std::uint32_t i = r.begin(); i != r.end(); ++i) {
        bounds[i] = primitive_bounds(prims, i);
        centroids[i] = (bounds[i].lo + bounds[i].hi) * Real(0.5);
        bvh.prims[i] = i;
      }
    });
    Builder builder{bounds, centroids, bvh.prims};
    const std::unique_ptr<BuildNode> root = builder.build(0, n, 1);
    bvh.nodes.reserve(2 * std::size_t(n));
    flatten(*root, bvh.nodes, 1, stats);
    bvh.nodes.shrink_to_fit();
  }
  stats.nodes = bvh.nodes.size();
  stats.bytes = bvh.nodes.size() * sizeof(BvhNode) + bvh.prims.size() * sizeof(std::uint32_t);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats_out) *stats_out = stats;
  return bvh;
}

}  // namespace strahl
