#include "strahl/accel/octree.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <stdexcept>

#include "strahl/accel/build_stats.h"

namespace strahl {

namespace {

// A node with at most this many primitives is not split. Leaves are tested a block of four
// triangles at a time (spatial.h), which makes bigger leaves cheap: on the bunny and the dragon
// (1 thread) 24 traces 10–30% faster than 8 or 16 (and 32, 48) with a third of the references
// and half the depth.
constexpr std::size_t kLeafSize = 24;
// When a split does not pay. By the surface area heuristic a ray through a cube passes
// through two of its eight octants on average (their surface areas over the cube's), so after
// the split it meets about a quarter of the octants' blocks, plus the cost of visiting
// octants (kTraversalCost, relative to one block test). A split is a bad refine when it
// saves less than kMinGain of the node's own cost, or when its octants list more than
// kMaxGrowth times the node's references: primitives large against the cube, which splitting
// copies more than it separates (unchecked, the cubes along the edge of a pile of coinciding
// triangles split down to the depth limit, each holding the whole pile). A few bad refines are
// tolerated on one path, to see past a local minimum: a layer of primitives in a centre plane is
// copied into both halves before the next level separates it.
constexpr Real kTraversalCost = 1;
constexpr Real kMinGain = 0.1;
constexpr Real kMaxGrowth = 2;
constexpr int kMaxBadRefines = 2;
// Blocks of four triangles needed for n primitives.
constexpr Real blocks(std::size_t n) {
  return Real((n + std::size_t(kernel::kTriangleBlockWidth) - 1) / std::size_t(kernel::kTriangleBlockWidth));
}
constexpr std::size_t kMaxIndex = (std::size_t(1) << 31) - 1;

struct Builder {
  const PrimitiveSet& set;
  const std::vector<Bounds>& bounds;  // padded
  Real pad;
  std::vector<OctreeNode> nodes;
  std::vector<std::uint32_t> refs;
  AccelBuildStats stats;

  OctreeNode leaf(const std::vector<std::uint32_t>& prims, int depth) {
    OctreeNode n;
    if (prims.size() > kMaxIndex) throw std::length_error("octree: too many primitives in one leaf");
    if (prims.size() == 1) {
      n.index = prims[0];
    } else {
      n.index = std::uint32_t(refs.size());
      refs.insert(refs.end(), prims.begin(), prims.end());
    }
    n.bits = 1u | std::uint32_t(prims.size()) << 1;
    ++stats.leaves;
    stats.primitive_references += prims.size();
    stats.max_depth = std::max(stats.max_depth, std::size_t(depth) + 1);
    return n;
  }

  // The node of the cube centred at `center` with half side `half`; its children are appended.
  // Child centres are computed as the traversal computes them (center ± half/2).
  OctreeNode build(const Vec3& center, Real half, std::vector<std::uint32_t> prims, int depth, int bad_refines) {
    if (prims.size() <= kLeafSize || depth + 1 >= kOctreeMaxDepth) return leaf(prims, depth);
    const Real child_half = half * Real(0.5);
    std::array<std::vector<std::uint32_t>, 8> children;
    std::size_t total = 0, occupied = 0, separated = 0;
    Real total_blocks = 0;
    for (std::uint32_t k = 0; k < 8; ++k) {
      // The octant's box, its inner faces exactly on the centre planes.
      Bounds box;
      box.lo = {k & 1u ? center.x : center.x - half, k & 2u ? center.y : center.y - half,
                k & 4u ? center.z : center.z - half};
      box.hi = {k & 1u ? center.x + half : center.x, k & 2u ? center.y + half : center.y,
                k & 4u ? center.z + half : center.z};
      // Listed where any part of it comes within the padding (spatial.h): a triangle crossing
      // the corner of an octant's box without touching the octant is not.
      for (std::uint32_t p : prims)
        if (overlaps(bounds[p], box) && !clipped_bounds(set, p, box, pad).empty()) children[k].push_back(p);
      total += children[k].size();
      total_blocks += blocks(children[k].size());
      occupied += !children[k].empty();
      separated += !children[k].empty() && children[k].size() < prims.size();
    }
    if (kTraversalCost + total_blocks / 4 > (1 - kMinGain) * blocks(prims.size()) ||
        Real(total) > kMaxGrowth * Real(prims.size()))
      ++bad_refines;
    // Several octants each holding every primitive (a pile of coinciding ones, a layer of
    // overlapping ones covering the cube): the split only copies them.
    if ((occupied > 1 && separated == 0) || bad_refines > kMaxBadRefines) return leaf(prims, depth);
    prims = {};
    const std::size_t first = nodes.size();
    if (first + 8 > kMaxIndex) throw std::length_error("octree: too many nodes");
    nodes.resize(first + 8);
    OctreeNode inner;
    inner.index = std::uint32_t(first);
    for (std::uint32_t k = 0; k < 8; ++k) {
      Vec3 c;
      c.x = center.x + (k & 1u ? child_half : -child_half);
      c.y = center.y + (k & 2u ? child_half : -child_half);
      c.z = center.z + (k & 4u ? child_half : -child_half);
      const OctreeNode child = build(c, child_half, std::move(children[k]), depth + 1, bad_refines);
      nodes[first + k] = child;
      if (!(child.is_leaf() && child.count() == 0)) inner.bits |= 2u << k;
    }
    return inner;
  }
};

}  // namespace

Octree build_octree(const PrimitiveSet& prims, AccelBuildStats* stats_out) {
  const auto start = std::chrono::steady_clock::now();
  const std::uint32_t n = prims.size();
  Octree oct;
  AccelBuildStats stats;
  stats.primitives = n;
  if (n > 0) {
    PaddedBounds padded_bounds = padded_primitive_bounds(prims);
    std::vector<Bounds>& bounds = padded_bounds.prims;
    const Real pad = padded_bounds.pad;
    const Bounds box = padded_bounds.scene;
    oct.center = (box.lo + box.hi) * Real(0.5);
    oct.half = max_component(box.hi - box.lo) * Real(0.5) + pad;

    std::vector<std::uint32_t> all(n);
    for (std::uint32_t i = 0; i < n; ++i) all[i] = i;
    Builder builder{prims, bounds, pad, {}, {}, {}};
    builder.nodes.resize(1);
    const OctreeNode root = builder.build(oct.center, oct.half, std::move(all), 0, 0);
    builder.nodes[0] = root;
    oct.nodes = std::move(builder.nodes);
    oct.nodes.shrink_to_fit();
    // The leaves' blocks, filled in node order (siblings' leaves lie together).
    for (OctreeNode& node : oct.nodes) {
      if (!node.is_leaf()) continue;
      const std::uint32_t count = node.count();
      const std::uint32_t first = std::uint32_t(oct.leaves.size());
      const std::uint32_t n_blocks =
          append_leaf(prims, count == 1 ? &node.index : builder.refs.data() + node.index, count, oct.leaves);
      node.index = count > 0 ? first : 0;
      node.bits = 1u | n_blocks << 1;
    }
    oct.leaves.shrink_to_fit();
    stats.leaves = builder.stats.leaves;
    stats.max_depth = builder.stats.max_depth;
    stats.primitive_references = builder.stats.primitive_references;
  }
  stats.nodes = oct.nodes.size();
  stats.bytes = oct.nodes.size() * sizeof(OctreeNode) + oct.leaves.size() * sizeof(SpatialLeaf);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats_out) *stats_out = stats;
  return oct;
}

}  // namespace strahl
