#pragma once
// Octree, the lecture's hierarchical subdivision: a cube around the scene, each cube split at its
// centre into eight until it holds few primitives or the depth limit is reached; a primitive is
// listed in every child its (padded) bounds overlap. The eight children of a node lie together.
// Traversal visits the children a ray passes through in the order it enters them — the
// parametric approach of Revelles et al. (2000): the three centre planes cut the ray's interval
// in the node into at most four pieces, each inside one child — and hands each leaf's own
// parameter interval to the visitor (see spatial.h). Leaves hold copies of their triangles' vertices
// in blocks of four (SpatialLeaf, spatial.h), tested four at once by octree_nearest and octree_occluded.

#include <cstdint>
#include <vector>

#include "strahl/accel/spatial.h"
#include "strahl/accel/traversal.h"

namespace strahl {

inline constexpr int kOctreeMaxDepth = 16;

struct OctreeNode {
  // Inner: the index of the first of its eight children, child k holding the octant with
  // x above the centre when bit 0 of k is set, y for bit 1, z for bit 2. Leaf: its first block in
  // the leaf array.
  std::uint32_t index = 0;
  // Bit 0: set for a leaf. Leaf, bits 1–31: its number of blocks (while building: primitives). Inner, bits 1–8: which
  // children are not empty leaves (bit 1 + k for child k), so that empty ones are skipped
  // without reading them.
  std::uint32_t bits = 0;

  STRAHL_HOST_DEVICE bool is_leaf() const { return (bits & 1u) != 0; }
  STRAHL_HOST_DEVICE std::uint32_t count() const { return bits >> 1; }
  STRAHL_HOST_DEVICE bool has_child(std::uint32_t k) const { return ((bits >> (1 + k)) & 1u) != 0; }
};
static_assert(sizeof(OctreeNode) == 8);

struct OctreeView {
  const OctreeNode* nodes = nullptr;
  const SpatialLeaf* leaves = nullptr;  // the leaves' blocks, each leaf's together
  Vec3 center;    // of the root cube
  Real half = 0;  // half its side
};

struct Octree {
  std::vector<OctreeNode> nodes;
  std::vector<SpatialLeaf> leaves;
  Vec3 center;
  Real half = 0;
  OctreeView view() const { return {nodes.data(), leaves.data(), center, half}; }
};

struct AccelBuildStats;
Octree build_octree(const PrimitiveSet& prims, AccelBuildStats* stats = nullptr);

// Calls leaf(first, count, leaf_t_lo, leaf_t_hi, t_max) for the blocks of every non-empty leaf the
// ray passes through within (t_min, t_max), nearer leaves first; leaf_t_hi is the plane's t itself
// (the visitor traversal below hands on next_up of it, spatial.h). leaf may lower t_max and returns
// true to stop at once; the traversal stops after a leaf once t_max lies within it.
template <class Leaf>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void traverse_leaves(const OctreeView& oct, const Ray& ray, Real t_min,
                                                           Real& t_max, Leaf& leaf) {
  if (oct.nodes == nullptr) return;
  const Vec3 inv = reciprocal(ray.direction);
  Bounds cube;
  cube.lo = oct.center - Vec3(oct.half);
  cube.hi = oct.center + Vec3(oct.half);
  Real lo, hi;
  if (!clip_to_box(cube, ray.origin, inv, t_min, t_max, lo, hi)) return;
  const Real origin[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  const Real inv_dir[3] = {inv.x, inv.y, inv.z};
  // Octant bits of the side of a centre plane the ray starts on, before it crosses the plane:
  // the low side for a positive direction component, the high side for a negative one (−0 too).
  const std::uint32_t negative = std::uint32_t(std::signbit(ray.direction.x)) |
                                 std::uint32_t(std::signbit(ray.direction.y)) << 1 |
                                 std::uint32_t(std::signbit(ray.direction.z)) << 2;
  struct Entry {
    std::uint32_t node;
    Real lo, hi;
    Real center[3];
    Real half;
  };
  Entry stack[3 * kOctreeMaxDepth];  // each level leaves at most three siblings waiting
  int top = 0;
  std::uint32_t node = 0;
  Real center[3] = {oct.center.x, oct.center.y, oct.center.z};
  Real half = oct.half;
  for (;;) {
    const OctreeNode n = oct.nodes[node];
    if (!n.is_leaf()) {
      // Where the ray meets the three centre planes; which of them it crosses inside the node,
      // in order; and the octant it starts in (a plane met at or before lo is already crossed;
      // a ray lying in a plane, NaN, counts as having crossed it).
      Real t_plane[3];
      int order[3], crossings = 0;
      std::uint32_t octant = negative;
      for (int a = 0; a < 3; ++a) {
        t_plane[a] = (center[a] - origin[a]) * inv_dir[a];
        if (!(t_plane[a] > lo)) octant ^= 1u << a;
        else if (t_plane[a] < hi) order[crossings++] = a;
      }
      for (int i = 1; i < crossings; ++i)
        for (int j = i; j > 0 && t_plane[order[j]] < t_plane[order[j - 1]]; --j) {
          const int tmp = order[j];
          order[j] = order[j - 1];
          order[j - 1] = tmp;
        }
      // The pieces [lo, t1], [t1, t2], …, [tk, hi], each in one octant: the far ones pushed
      // (farthest first), the nearest non-empty one entered at once.
      std::uint32_t octants[4];
      Real cut[5];
      cut[0] = lo;
      octants[0] = octant;
      for (int i = 0; i < crossings; ++i) {
        cut[i + 1] = t_plane[order[i]];
        octants[i + 1] = octants[i] ^ (1u << order[i]);
      }
      cut[crossings + 1] = hi;
      const Real child_half = half * Real(0.5);
      int next = -1;
      for (int i = crossings; i >= 0; --i) {
        // Skip empty children, and pieces of no length (two planes met at once: a child touched in a point).
        if (!n.has_child(octants[i]) || !(cut[i] < cut[i + 1])) continue;
        if (next >= 0) {
          Entry& e = stack[top++];
          e.node = n.index + octants[next];
          e.lo = cut[next];
          e.hi = cut[next + 1];
          for (int a = 0; a < 3; ++a) e.center[a] = center[a] + ((octants[next] >> a) & 1u ? child_half : -child_half);
          e.half = child_half;
        }
        next = i;
      }
      if (next >= 0) {
        node = n.index + octants[next];
        lo = cut[next];
        hi = cut[next + 1];
        for (int a = 0; a < 3; ++a) center[a] += (octants[next] >> a) & 1u ? child_half : -child_half;
        half = child_half;
        continue;
      }
    } else {
      const std::uint32_t count = n.count();
      if (count > 0 && leaf(oct.leaves + n.index, count, lo, hi, t_max)) return;
      // Every leaf nearer than hi has been searched: a hit before it is the nearest.
      if (t_max <= hi) return;
    }
    if (top == 0) return;
    const Entry& e = stack[--top];
    if (e.lo >= t_max) return;  // the rest lies beyond a hit already found
    node = e.node;
    lo = e.lo;
    hi = e.hi;
    center[0] = e.center[0];
    center[1] = e.center[1];
    center[2] = e.center[2];
    half = e.half;
  }
}

// Calls visitor(prim, leaf_t_lo, leaf_t_hi, t_max) for the primitives of every leaf the ray
// passes through within (t_min, t_max), nearer leaves first, and stops after a leaf once t_max
// (which the visitor may lower) lies within it; see traversal.h for the visitor contract. The
// nearest-hit and any-hit queries are spatial_nearest / spatial_occluded (spatial.h).
template <class Visitor>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void traverse(const OctreeView& oct, const Ray& ray, Real t_min, Real& t_max,
                                                     Visitor& visit) {
  spatial_traverse(oct, ray, t_min, t_max, visit);
}

}  // namespace strahl
