#pragma once
// Octree, the lecture's hierarchical subdivision: a cube around the scene, each cube split at its
// centre into eight until it holds few primitives or the depth limit is reached; a primitive is
// listed in every child its (padded) bounds overlap. The eight children of a node lie together.
// Traversal visits the children a ray passes through in the order it enters them: it walks from
// leaf to leaf along ropes (spatial.h), descending at each node into the octant that holds the
// ray just after the current t (which of the three centre planes it has crossed by then), and
// hands each leaf's own parameter interval to the visitor. Leaves hold copies of their triangles'
// vertices in blocks of four (SpatialLeaf, spatial.h), tested four at once.

#include <cstdint>
#include <vector>

#include "strahl/accel/spatial.h"
#include "strahl/accel/traversal.h"

namespace strahl {

// Centres are float offsets from the cube's corner, resolving 2⁻²⁴ of its side: at depth 16 a
// cube is still 2⁸ float steps wide.
inline constexpr int kOctreeMaxDepth = 16;

struct OctreeNode {
  // Inner: the index of the first of its eight children, child k holding the octant with x above
  // the centre when bit 0 of k is set, y for bit 1, z for bit 2. Leaf: its index in the leaf array.
  std::uint32_t index = 0;
  // Bit 0: set for a leaf. Leaf, bits 1–31: its number of primitives while building, 0 after (the
  // leaf's blocks and their count are in its OctreeLeaf).
  std::uint32_t bits = 0;

  STRAHL_HOST_DEVICE bool is_leaf() const { return (bits & 1u) != 0; }
  STRAHL_HOST_DEVICE std::uint32_t count() const { return bits >> 1; }
  // Inner: its centre's entry in the centre array (children come in groups of eight after the root).
  STRAHL_HOST_DEVICE std::uint32_t group() const { return (index - 1) >> 3; }
};
static_assert(sizeof(OctreeNode) == 8);

// The centre of an inner node's cube, where its three dividing planes meet: float offsets from
// OctreeView::base, as the kd-tree stores its splits (the build sorts primitives by these very
// planes, base + offset).
struct OctreeCenter {
  float offset[3];
};

// A leaf: its blocks, its box (faces at its ancestors' centre planes, the same float offsets) and
// its ropes (spatial.h).
using OctreeLeaf = RopedLeaf<float>;

struct OctreeView {
  const OctreeNode* nodes = nullptr;
  const OctreeCenter* centers = nullptr;  // per inner node, by group()
  const OctreeLeaf* leaves = nullptr;
  const SpatialLeaf* blocks = nullptr;  // the leaves' blocks, each leaf's together
  Bounds bounds;                        // of every primitive (padded): rays are clipped to these
  Vec3 base;                            // plane positions are stored relative to this point (the cube's corner)
};

struct Octree {
  LargeArray<OctreeNode> nodes;
  LargeArray<OctreeCenter> centers;
  LargeArray<OctreeLeaf> leaves;
  LargeArray<SpatialLeaf> blocks;
  Vec3 center;    // of the root cube
  Real half = 0;  // half its side
  Bounds cube;    // [center − half, center + half]
  Bounds bounds;  // of the primitives (padded), within the cube
  OctreeView view() const { return {nodes.data(), centers.data(), leaves.data(), blocks.data(), bounds, cube.lo}; }
};

struct AccelBuildStats;
Octree build_octree(const PrimitiveSet& prims, AccelBuildStats* stats = nullptr);

// Calls leaf(first, count, leaf_t_lo, leaf_t_hi, t_max) for the blocks of every non-empty leaf the
// ray passes through within (t_min, t_max), nearer leaves first, along the ropes (spatial.h).
template <class Leaf>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void traverse_leaves(const OctreeView& oct, const Ray& ray, Real t_min,
                                                           Real& t_max, Leaf& leaf) {
  if (oct.nodes == nullptr) return;
  auto descend = [&oct](std::uint32_t node, const WalkRay& r, Real lo) {
    // Octant bits of the side of each centre plane the ray is on just after lo: it starts on the
    // low side for a positive direction component, the high side for a negative one (−0 too),
    // and is on the other once the plane is met at or before lo.
    const std::uint32_t start = std::uint32_t(r.negative[0]) | std::uint32_t(r.negative[1]) << 1 |
                                std::uint32_t(r.negative[2]) << 2;
    OctreeNode n = oct.nodes[node];
    while (!n.is_leaf()) {
      const OctreeCenter& c = oct.centers[n.group()];
      std::uint32_t octant = start;
      for (int a = 0; a < 3; ++a) {
        const Real t_plane = (Real(c.offset[a]) - r.origin[a]) * r.inv_dir[a];
        if (!(t_plane > lo)) octant ^= 1u << a;
      }
      n = oct.nodes[n.index + octant];
    }
    return n.index;
  };
  // Clipped to the primitives' bounds rather than the cube: a long or flat scene leaves much of its
  // cube empty, and a ray need not walk the empty leaves there.
  rope_walk(oct.bounds, oct.base, oct.leaves, oct.blocks, ray, t_min, t_max, descend, leaf);
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
