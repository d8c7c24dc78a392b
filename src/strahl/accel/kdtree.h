#pragma once
// kd-tree: axis-aligned splitting planes chosen by the surface area heuristic, built in
// O(n log n) from bound events sorted once and kept sorted while splitting (Wald & Havran 2006);
// primitives straddling a plane are listed on both sides, triangles clipped to each side
// ("perfect splits"). Nodes are 8 bytes (as in pbrt): a split position or a leaf's number, and
// two bits of kind. Leaves hold copies of their triangles' vertices in blocks of four
// (SpatialLeaf, spatial.h), tested four at once.
// Traversal walks from leaf to leaf along ropes (spatial.h). The queries (nearest hit, occlusion,
// visitor) are spatial.h's, over traverse_leaves below, which hands each leaf's own parameter
// interval on.

#include <cstdint>
#include <vector>

#include "strahl/accel/spatial.h"
#include "strahl/accel/traversal.h"

namespace strahl {

inline constexpr int kKdMaxDepth = 48;  // the build's recursion (and the ropes' linking) go no deeper

struct KdNode {
  // Inner: the split position as an offset from KdTreeView::base (a float keeps nodes at 8 bytes;
  // relative to the scene's corner it resolves the scene to ~1e-7 of its size). Leaf: its index
  // in the leaf array (KdLeaf).
  union {
    float split;
    std::uint32_t prims;
  };
  // Bits 0–1: split axis (0, 1, 2) or 3 for a leaf. Bits 2–31: inner, the index of the child
  // above the plane (the one below follows the node); leaf, its number of primitives while
  // building, 0 after (the leaf's blocks and their count are in its KdLeaf).
  std::uint32_t bits;

  STRAHL_HOST_DEVICE bool is_leaf() const { return (bits & 3u) == 3u; }
  STRAHL_HOST_DEVICE std::uint32_t axis() const { return bits & 3u; }
  STRAHL_HOST_DEVICE std::uint32_t above_child() const { return bits >> 2; }
  STRAHL_HOST_DEVICE std::uint32_t count() const { return bits >> 2; }  // while building
};
static_assert(sizeof(KdNode) == 8);

// A leaf: its blocks, its box (faces as float offsets from KdTreeView::base, like splits) and its
// ropes (spatial.h).
using KdLeaf = RopedLeaf<float>;
static_assert(sizeof(KdLeaf) == 56);

struct KdTreeView {
  const KdNode* nodes = nullptr;
  const KdLeaf* leaves = nullptr;
  const SpatialLeaf* blocks = nullptr;  // the leaves' blocks, each leaf's together
  Bounds bounds;  // of every leaf together (the primitives' padded bounds)
  Vec3 base;      // split positions are stored relative to this point (bounds.lo)
};

struct KdTree {
  LargeArray<KdNode> nodes;
  LargeArray<KdLeaf> leaves;
  LargeArray<SpatialLeaf> blocks;
  Bounds bounds;
  Vec3 base;
  KdTreeView view() const { return {nodes.data(), leaves.data(), blocks.data(), bounds, base}; }
};

struct AccelBuildStats;
KdTree build_kdtree(const PrimitiveSet& prims, AccelBuildStats* stats = nullptr);

// Calls leaf(first, count, leaf_t_lo, leaf_t_hi, t_max) for the blocks of every non-empty leaf the
// ray passes through within (t_min, t_max), nearer leaves first, along the ropes (spatial.h).
template <class Leaf>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void traverse_leaves(const KdTreeView& kd, const Ray& ray, Real t_min,
                                                           Real& t_max, Leaf& leaf) {
  if (kd.nodes == nullptr) return;
  auto descend = [&kd](std::uint32_t node, const WalkRay& r, Real lo) {
    KdNode n = kd.nodes[node];
    while (!n.is_leaf()) {
      const std::uint32_t axis = n.axis();
      const Real t_plane = (Real(n.split) - r.origin[axis]) * r.inv_dir[axis];
      const std::uint32_t below = node + 1, above = n.above_child();
      const std::uint32_t near = r.negative[axis] ? above : below, far = r.negative[axis] ? below : above;
      node = t_plane <= lo ? far : near;
      n = kd.nodes[node];
    }
    return n.prims;
  };
  rope_walk(kd.bounds, kd.base, kd.leaves, kd.blocks, ray, t_min, t_max, descend, leaf);
}

// Calls visitor(prim, leaf_t_lo, leaf_t_hi, t_max) for the primitives of every leaf the ray
// passes through within (t_min, t_max), nearer leaves first, and stops after a leaf once t_max
// (which the visitor may lower) lies within it; see traversal.h for the visitor contract. The
// nearest-hit and any-hit queries are spatial_nearest / spatial_occluded (spatial.h).
template <class Visitor>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void traverse(const KdTreeView& kd, const Ray& ray, Real t_min, Real& t_max,
                                                     Visitor& visit) {
  spatial_traverse(kd, ray, t_min, t_max, visit);
}

}  // namespace strahl
