#pragma once
// kd-tree: axis-aligned splitting planes chosen by the surface area heuristic, built in
// O(n log n) from bound events sorted once and kept sorted while splitting (Wald & Havran 2006);
// primitives straddling a plane are listed on both sides, triangles clipped to each side
// ("perfect splits"). Nodes are 8 bytes (as in pbrt): a split position or a range of leaf entries,
// and two bits of kind. Leaves hold copies of their triangles' vertices in blocks of four
// (SpatialLeaf, spatial.h), tested four at once.
// Traversal runs front to back with a fixed stack; nearest hit and occlusion test each leaf's
// entries directly (kdtree_nearest, kdtree_occluded), the visitor traversal (for_each_crossing)
// hands each leaf's own parameter interval to the visitor (see spatial.h).

#include <cstdint>
#include <vector>

#include "strahl/accel/spatial.h"
#include "strahl/accel/traversal.h"

namespace strahl {

inline constexpr int kKdMaxDepth = 48;  // the traversal stack holds one entry per level

struct KdNode {
  // Inner: the split position as an offset from KdTreeView::base (a float keeps nodes at 8 bytes;
  // relative to the scene's corner it resolves the scene to ~1e-7 of its size). Leaf: its first
  // block in the leaf array.
  union {
    float split;
    std::uint32_t prims;
  };
  // Bits 0–1: split axis (0, 1, 2) or 3 for a leaf. Bits 2–31: inner, the index of the child
  // above the plane (the one below follows the node); leaf, its number of blocks.
  std::uint32_t bits;

  STRAHL_HOST_DEVICE bool is_leaf() const { return (bits & 3u) == 3u; }
  STRAHL_HOST_DEVICE std::uint32_t axis() const { return bits & 3u; }
  STRAHL_HOST_DEVICE std::uint32_t above_child() const { return bits >> 2; }
  STRAHL_HOST_DEVICE std::uint32_t count() const { return bits >> 2; }  // (while building: primitives)
};
static_assert(sizeof(KdNode) == 8);

struct KdTreeView {
  const KdNode* nodes = nullptr;
  const SpatialLeaf* leaves = nullptr;  // the leaves' blocks, each leaf's together
  Bounds bounds;  // of every leaf together (the primitives' padded bounds)
  Vec3 base;      // split positions are stored relative to this point (bounds.lo)
};

struct KdTree {
  std::vector<KdNode> nodes;
  std::vector<SpatialLeaf> leaves;
  Bounds bounds;
  Vec3 base;
  KdTreeView view() const { return {nodes.data(), leaves.data(), bounds, base}; }
};

struct AccelBuildStats;
KdTree build_kdtree(const PrimitiveSet& prims, AccelBuildStats* stats = nullptr);

// Calls leaf(first, count, leaf_t_lo, leaf_t_hi, t_max) for the blocks of every non-empty leaf the
// ray passes through within (t_min, t_max), nearer leaves first; leaf_t_hi is the plane's t itself
// (the visitor traversal below hands on next_up of it, spatial.h). leaf may lower t_max and returns
// true to stop at once; the traversal stops after a leaf once t_max lies within it.
template <class Leaf>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void traverse_leaves(const KdTreeView& kd, const Ray& ray, Real t_min,
                                                           Real& t_max, Leaf& leaf) {
  if (kd.nodes == nullptr) return;
  const Vec3 inv = reciprocal(ray.direction);
  Real lo, hi;
  if (!clip_to_box(kd.bounds, ray.origin, inv, t_min, t_max, lo, hi)) return;
  const Real origin[3] = {ray.origin.x - kd.base.x, ray.origin.y - kd.base.y, ray.origin.z - kd.base.z};
  const Real inv_dir[3] = {inv.x, inv.y, inv.z};
  // Which side of a plane the ray starts on follows from the sign of its direction, −0 included.
  const bool negative[3] = {std::signbit(ray.direction.x), std::signbit(ray.direction.y),
                            std::signbit(ray.direction.z)};
  struct Entry {
    std::uint32_t node;
    Real lo, hi;
  };
  Entry stack[kKdMaxDepth];
  int top = 0;
  std::uint32_t node = 0;
  for (;;) {
    const KdNode n = kd.nodes[node];
    if (!n.is_leaf()) {
      const std::uint32_t axis = n.axis();
      const Real t_plane = (Real(n.split) - origin[axis]) * inv_dir[axis];
      const std::uint32_t below = node + 1, above = n.above_child();
      const std::uint32_t near = negative[axis] ? above : below, far = negative[axis] ? below : above;
      if (t_plane <= lo) {
        node = far;  // the plane lies behind the part of the ray inside this node
      } else if (t_plane < hi) {
        stack[top++] = {far, t_plane, hi};
        node = near;
        hi = t_plane;
      } else {
        node = near;  // beyond it, or never crossed (parallel; NaN when the ray lies in the plane)
      }
      continue;
    }
    const std::uint32_t count = n.count();
    if (count > 0 && leaf(kd.leaves + n.prims, count, lo, hi, t_max)) return;
    // Every leaf nearer than hi has been searched: a hit before it is the nearest.
    if (t_max <= hi) return;
    if (top == 0) return;
    --top;
    node = stack[top].node;
    lo = stack[top].lo;
    hi = stack[top].hi;
  }
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
