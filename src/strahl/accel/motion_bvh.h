#pragma once
// The moving shapes' BVH (motion blur), one tree per time segment of the shutter. A tree over the
// boxes each shape sweeps during the whole shutter grows loose where shapes turn or travel far:
// a torus turning by 60° sweeps boxes far larger than its triangles, and rays pass them all.
// Cut the shutter into K equal segments, each with a tree over the boxes swept within it, and
// the boxes shrink towards the shapes' own; a ray at time u traverses only the tree of the
// segment holding u. The hits are the same as with one tree (each tree bounds every shape at
// every time of its segment); K is chosen by the build from how much the boxes shrink.
//
// The trees are 8-wide (accel/wide_bvh.h: a binary SAH tree collapsed, one SIMD box test for a
// node's eight children, the same conservative float boxes and traversal as the scene's BVH).
// The K trees lie one after another in one node array, each with child indices relative to its
// own first node, and share one array of leaf entries (the shapes' indices): a segment is an
// IndexTreeView, and the GPU uploads two arrays.

#include <cstdint>
#include <functional>
#include <vector>

#include "strahl/accel/bvh.h"
#include "strahl/accel/wide_bvh.h"
#include "strahl/geometry/moving.h"
#include "strahl/geometry/moving_instance.h"
#include "strahl/geometry/moving_solid.h"
#include "strahl/util/large_array.h"

namespace strahl {

inline constexpr std::uint32_t kMaxMotionSegments = 16;
inline constexpr int kMotionSegmentCounts = 5;  // the K tried: 1, 2, 4, 8, 16
static_assert(1u << (kMotionSegmentCounts - 1) == kMaxMotionSegments);

struct MotionBvhView {
  IndexTreeView trees;  // the K trees: their nodes one after another, their leaves' entries shared
  std::uint32_t segments = 0;  // K, a power of two; 0 when nothing moves
  std::uint32_t first_node[kMaxMotionSegments] = {};  // where segment k's tree begins in trees.nodes

  // The tree of the segment holding u ∈ [0, 1]. Segment k covers [k/K, (k + 1)/K]; K is a power
  // of two, so u·K is exact and k = ⌊u·K⌋ has k/K ≤ u ≤ (k + 1)/K in floating point too.
  STRAHL_HOST_DEVICE IndexTreeView segment_at(Real u) const {
    if (segments == 0) return {};
    const Real x = u * Real(segments);
    std::uint32_t k = 0;
    if (x >= 1) k = x >= Real(segments) ? segments - 1 : static_cast<std::uint32_t>(x);
    IndexTreeView tree = trees;
    if (tree.nodes != nullptr) tree.nodes += first_node[k];
    return tree;
  }
};

struct MotionBvh {
  // The K trees' nodes (each tree's boxes those swept in its segment) and the leaves' entries,
  // shared; root_leaf_count > 0: each tree is one leaf of all the shapes (no nodes); extent: the
  // largest |coordinate| of any box of any segment, per axis.
  IndexTree trees;
  std::uint32_t segments = 0;
  std::uint32_t first_node[kMaxMotionSegments] = {};
  // Σ of the primitives' surface areas over the segments' boxes, averaged over the segments, for
  // each K = 1, 2, 4, …, kMaxMotionSegments tried (the build's measure; 0 past those tried).
  double swept_area[kMotionSegmentCounts] = {};

  MotionBvhView view() const;
};

// The box primitive `prim` sweeps over the shutter fractions [u0, u1].
using SweptBox = std::function<Bounds(std::uint32_t prim, Real u0, Real u1)>;

// Builds the trees over `count` primitives: one tree over the shapes where they are at
// mid-shutter, its boxes refitted to each segment (one SAH build, K passes over the nodes; the
// shapes' order is shared). K doubles from 1 while that cuts the summed surface area of the boxes
// by at least a fifth (the expected box and primitive tests of a ray fall with it; a twentieth
// while K·count ≤ 4096, whose trees cost next to nothing; K = 1 where the tree is one leaf without
// a box, as a few spheres and triangles are), up to
// kMaxMotionSegments and to K·count ≤ 2^20 (the K trees' nodes: about 40 bytes for each shape
// in each segment). `segments` > 0 forces K (a power of two ≤ kMaxMotionSegments; the tests).
// Primitives from first_costly on (solids, instances: each brings the ray to where it stands
// still, at_time(), before its own test) are leaves the SAH weighs one by one, and are never
// visited without a box test (a tree of one leaf holding one gets a root node).
MotionBvh build_motion_bvh(std::uint32_t count, const SweptBox& box, std::uint32_t segments = 0,
                           std::uint32_t first_costly = ~std::uint32_t(0));

// The same over a scene's moving shapes: the spheres, then the triangles, the solids and the
// instances, numbered on (render/moving_shapes.h).
MotionBvh build_motion_bvh(const std::vector<kernel::MovingSphere>& spheres,
                           const std::vector<kernel::MovingTriangle>& triangles,
                           const std::vector<kernel::MovingSolid>& solids = {},
                           const std::vector<kernel::MovingInstance>& instances = {}, std::uint32_t segments = 0);

}  // namespace strahl
