#include "strahl/accel/octree.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
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
  const LargeArray<Bounds>& bounds;  // padded
  Real pad;
  Vec3 base;
  LargeArray<OctreeNode> nodes;
  LargeArray<OctreeCenter> centers;
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

  // The node of the cube `box` (its faces the planes the traversal meets: base + a float offset)
  // with centre `center` (offsets from base) and half side `half`; its children are appended.
  OctreeNode build(const Bounds& box, const OctreeCenter& center, Real half, std::vector<std::uint32_t> prims,
                   int depth, int bad_refines) {
    if (prims.size() <= kLeafSize || depth + 1 >= kOctreeMaxDepth) return leaf(prims, depth);
    const Real child_half = half * Real(0.5);
    const Vec3 plane(base.x + Real(center.offset[0]), base.y + Real(center.offset[1]), base.z + Real(center.offset[2]));
    std::array<Bounds, 8> boxes;
    std::array<std::vector<std::uint32_t>, 8> children;
    std::size_t total = 0, occupied = 0, separated = 0;
    Real total_blocks = 0;
    for (std::uint32_t k = 0; k < 8; ++k) {
      // The octant's box, its inner faces exactly on the centre planes.
      Bounds& octant = boxes[k];
      octant.lo = {k & 1u ? plane.x : box.lo.x, k & 2u ? plane.y : box.lo.y, k & 4u ? plane.z : box.lo.z};
      octant.hi = {k & 1u ? box.hi.x : plane.x, k & 2u ? box.hi.y : plane.y, k & 4u ? box.hi.z : plane.z};
      // Listed where any part of it comes within the padding (spatial.h): a triangle crossing
      // the corner of an octant's box without touching the octant is not.
      for (std::uint32_t p : prims)
        if (overlaps(bounds[p], octant) && !clipped_bounds(set, p, octant, pad).empty()) children[k].push_back(p);
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
    centers.push_back(center);  // at inner.group(): groups are appended in order
    for (std::uint32_t k = 0; k < 8; ++k) {
      OctreeCenter c;
      for (int a = 0; a < 3; ++a)
        c.offset[a] = float(Real(center.offset[a]) + ((k >> a) & 1u ? child_half : -child_half));
      nodes[first + k] = build(boxes[k], c, child_half, std::move(children[k]), depth + 1, bad_refines);
    }
    return inner;
  }
};

// Fills in every leaf's box and ropes (OctreeLeaf, spatial.h), walking down from the root with the
// box of the node at hand and the ropes of its faces.
struct Linker {
  const LargeArray<OctreeNode>& nodes;
  const LargeArray<OctreeCenter>& centers;
  LargeArray<OctreeLeaf>& leaves;

  // The deepest node below `target` (beyond face f of a leaf with box `face`) whose cube still
  // holds the whole face, octant by octant (rope_side, spatial.h).
  std::uint32_t push_down(std::uint32_t target, int f, const float (&face)[6]) const {
    if (target == kNoRope) return target;
    for (;;) {
      const OctreeNode& n = nodes[target];
      if (n.is_leaf()) return target;
      std::uint32_t octant = 0;
      for (int b = 0; b < 3; ++b) {
        const int side = rope_side(b, centers[n.group()].offset[b], f, face);
        if (side < 0) return target;
        octant |= std::uint32_t(side) << b;
      }
      target = n.index + octant;
    }
  }

  void link(std::uint32_t node, const float (&face)[6], const std::uint32_t (&rope)[6]) {
    const OctreeNode& n = nodes[node];
    if (n.is_leaf()) {
      OctreeLeaf& leaf = leaves[n.index];
      for (int f = 0; f < 6; ++f) {
        leaf.face[f] = face[f];
        leaf.rope[f] = push_down(rope[f], f, face);
      }
      return;
    }
    const OctreeCenter& center = centers[n.group()];
    for (std::uint32_t k = 0; k < 8; ++k) {
      float child_face[6];
      std::uint32_t child_rope[6];
      for (int a = 0; a < 3; ++a) {
        const std::uint32_t sibling = n.index + (k ^ (1u << a));
        const bool above = (k >> a) & 1u;
        child_face[2 * a] = above ? center.offset[a] : face[2 * a];
        child_rope[2 * a] = above ? sibling : rope[2 * a];
        child_face[2 * a + 1] = above ? face[2 * a + 1] : center.offset[a];
        child_rope[2 * a + 1] = above ? rope[2 * a + 1] : sibling;
      }
      link(n.index + k, child_face, child_rope);
    }
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
    LargeArray<Bounds>& bounds = padded_bounds.prims;
    const Real pad = padded_bounds.pad;
    const Bounds box = padded_bounds.scene;
    oct.center = (box.lo + box.hi) * Real(0.5);
    // Half the side, a float (rounded up): the root's centre planes, base + float(half), then lie
    // at the centre itself wherever center − half is exact (a scene symmetric about 0: at 0).
    float half = float(max_component(box.hi - box.lo) * Real(0.5) + pad);
    if (Real(half) < max_component(box.hi - box.lo) * Real(0.5) + pad)
      half = std::nextafter(half, std::numeric_limits<float>::infinity());
    oct.half = Real(half);
    oct.cube = {oct.center - Vec3(oct.half), oct.center + Vec3(oct.half)};
    oct.bounds = box;

    std::vector<std::uint32_t> all(n);
    for (std::uint32_t i = 0; i < n; ++i) all[i] = i;
    Builder builder{prims, bounds, pad, oct.cube.lo, {}, {}, {}, {}};
    builder.nodes.resize(1);
    const OctreeCenter root_center = {{half, half, half}};
    const OctreeNode root = builder.build(oct.cube, root_center, oct.half, std::move(all), 0, 0);
    builder.nodes[0] = root;
    oct.nodes = std::move(builder.nodes);
    oct.nodes.shrink_to_fit();
    oct.centers = std::move(builder.centers);
    oct.centers.shrink_to_fit();
    // The leaves and their blocks, in node order (siblings' leaves lie together).
    oct.leaves.reserve(builder.stats.leaves);
    for (OctreeNode& node : oct.nodes) {
      if (!node.is_leaf()) continue;
      const std::uint32_t count = node.count();
      OctreeLeaf leaf{};
      leaf.first = std::uint32_t(oct.blocks.size());
      leaf.count =
          append_leaf(prims, count == 1 ? &node.index : builder.refs.data() + node.index, count, oct.blocks);
      node.index = std::uint32_t(oct.leaves.size());
      node.bits = 1u;  // the count lives in the leaf
      oct.leaves.push_back(leaf);
    }
    oct.blocks.shrink_to_fit();
    float face[6];
    std::uint32_t rope[6];
    unbounded_faces(face, rope);
    Linker{oct.nodes, oct.centers, oct.leaves}.link(0, face, rope);
    stats.leaves = builder.stats.leaves;
    stats.max_depth = builder.stats.max_depth;
    stats.primitive_references = builder.stats.primitive_references;
  }
  stats.nodes = oct.nodes.size();
  stats.bytes = oct.nodes.size() * sizeof(OctreeNode) + oct.centers.size() * sizeof(OctreeCenter) +
                oct.leaves.size() * sizeof(OctreeLeaf) + oct.blocks.size() * sizeof(SpatialLeaf);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats_out) *stats_out = stats;
  return oct;
}

}  // namespace strahl
