#pragma once
// What the space-subdividing structures (kd-tree, octree) share. They list a primitive in every
// leaf it overlaps, so their traversals hand each leaf's own parameter interval to the visitor
// (see traversal.h), and three things keep the queries equal to the naive loop's:
//
// 1. The intervals of the leaves a ray passes through tile its parameter line exactly: a leaf
//    ends at the very t value the next one starts with (the plane's t, computed once for both).
// 2. A leaf's upper end is handed on as next_up(t_exit): for_each_crossing counts a crossing in
//    the open interval (lo, hi), so a crossing lying exactly on a splitting plane (an
//    axis-aligned triangle in the plane, met by an axis-parallel ray) is counted once, in the
//    nearer leaf, instead of in neither.
// 3. Primitives are sorted into leaves by their bounds grown by a tiny margin (clipped_bounds,
//    below): a primitive is listed in every leaf it comes within the margin of, so a hit computed
//    a few ulps off the primitive still lies in a leaf that lists it, and a primitive touching or
//    lying in a splitting plane is listed on both sides. Together with 1 this also makes the
//    early exit exact: a primitive first listed in a later leaf cannot be hit before the current
//    leaf ends.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "strahl/accel/primitive.h"
#include "strahl/accel/traversal.h"
#include "strahl/accel/triangle_block.h"
#include "strahl/util/large_array.h"

namespace strahl {

// The smallest Real above t (t finite; ±∞ and NaN are returned as they are).
STRAHL_HOST_DEVICE inline Real next_up(Real t) {
  if (!(t < kInfinity)) return t;
  if (t == 0) return std::numeric_limits<Real>::denorm_min();
  std::uint64_t bits;
  std::memcpy(&bits, &t, sizeof bits);
  bits = t > 0 ? bits + 1 : bits - 1;
  std::memcpy(&t, &bits, sizeof bits);
  return t;
}

// The part [t_lo, t_hi] of (t_min, t_max) in which the ray is inside the box. Direction
// components of ±0 give ±∞ reciprocals: a ray parallel to a slab is inside it for all t or for
// none, and a ray lying in a face (0·∞ = NaN) counts as inside.
STRAHL_HOST_DEVICE inline bool clip_to_box(const Bounds& b, const Vec3& origin, const Vec3& inv_dir, Real t_min,
                                           Real t_max, Real& t_lo, Real& t_hi) {
  for (int a = 0; a < 3; ++a) {
    Real t0 = (b.lo[a] - origin[a]) * inv_dir[a];
    Real t1 = (b.hi[a] - origin[a]) * inv_dir[a];
    if (t0 > t1) { const Real tmp = t0; t0 = t1; t1 = tmp; }
    t_min = t0 > t_min ? t0 : t_min;  // NaN keeps the old bound
    t_max = t1 < t_max ? t1 : t_max;
    if (t_min > t_max) return false;
  }
  t_lo = t_min;
  t_hi = t_max;
  return true;
}

// A leaf is a run of triangle blocks (accel/triangle_block.h): its triangles' vertices copied, four
// side by side, contiguous with the leaf's others (no indirection through primitive indices and no
// 88-byte scene triangles in the hot loop) and tested four at once, bit for bit as
// intersect_primitive() tests them. Its spheres and solids sit in lanes of their own (the `other`
// bits) and are tested from the primitive set's arrays: they are few where speed matters. A
// primitive listed in several leaves is copied into each.
using SpatialLeaf = kernel::TriangleBlock;

// ---- Walking from leaf to leaf along ropes ----
// Both structures are walked the same way (Havran 1998; Popov et al. 2007): every leaf knows its
// box and, for each face, the deepest node beyond it whose box holds the whole face (its rope). A
// ray descends once from the root to the leaf it starts in; after each leaf it follows the rope
// of the face it leaves by and descends from there, instead of popping a stack and descending
// again from a far sibling high up the tree.
//
// Which child holds the ray just after lo is decided at every node by the plane's t against lo (a
// plane met at or before lo is crossed; a ray lying in it, NaN, has not crossed it), as a stack
// traversal decides it. A leaf ends where the ray meets the nearest of its faces ahead: the very t
// the next leaf starts with (rule 1 above), and the t a stack traversal would give (the same
// planes, the same arithmetic). Where the ray leaves by an edge or a corner (two faces at one t)
// the rope of one of them may lead into a leaf the ray only touches there: that leaf ends where it
// starts and is passed over (the ray leaves it at once by the other face), as a stack traversal
// never enters it. Ropes are pushed down at build time only where the choice is the one every
// ray leaving by the face makes, or such a touched leaf: never a leaf beyond where the ray is.

inline constexpr std::uint32_t kNoRope = 0xffffffffu;  // a face on the structure's bounds

// A leaf of a roped structure. Face 2a is the box's lower face on axis a, 2a + 1 the upper one: a
// face inside the structure is an ancestor's splitting plane, stored as the traversal reads it,
// one on the structure's bounds is ±∞ with rope kNoRope.
template <class Plane>
struct RopedLeaf {
  Plane face[6];
  std::uint32_t rope[6];
  std::uint32_t first;  // its first block in the block array
  std::uint32_t count;  // its number of blocks
};

// The ray as the descent reads it: origin relative to the structure's base, reciprocal direction,
// and the sign of each direction component (−0 included): which side of a plane it starts on.
struct WalkRay {
  Real origin[3];
  Real inv_dir[3];
  bool negative[3];
};

// Calls leaf(first, count, leaf_t_lo, leaf_t_hi, t_max) for the blocks of every non-empty leaf the
// ray passes through within (t_min, t_max), nearer leaves first; leaf_t_hi is the plane's t itself
// (the visitor traversal hands on next_up of it). leaf may lower t_max and returns true to stop at
// once; the walk stops after a leaf once t_max lies within it. descend(node, ray, lo) returns the
// leaf below `node` that holds the ray just after lo; `bounds` are the root's, `base` the point
// plane positions are relative to.
template <class Plane, class Descend, class Leaf>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void rope_walk(const Bounds& bounds, const Vec3& base,
                                                     const RopedLeaf<Plane>* leaves, const SpatialLeaf* blocks,
                                                     const Ray& ray, Real t_min, Real& t_max, Descend&& descend,
                                                     Leaf& leaf) {
  const Vec3 inv = reciprocal(ray.direction);
  Real lo, end;
  if (!clip_to_box(bounds, ray.origin, inv, t_min, t_max, lo, end)) return;
  const WalkRay r = {{ray.origin.x - base.x, ray.origin.y - base.y, ray.origin.z - base.z},
                     {inv.x, inv.y, inv.z},
                     {std::signbit(ray.direction.x), std::signbit(ray.direction.y), std::signbit(ray.direction.z)}};
  // The faces a ray leaves a box by: the upper one on an axis it goes up along.
  const int exit_face[3] = {r.negative[0] ? 0 : 1, r.negative[1] ? 2 : 3, r.negative[2] ? 4 : 5};
  std::uint32_t node = 0;
  bool first = true;
  for (;;) {
    const RopedLeaf<Plane>& l = leaves[descend(node, r, lo)];
    Real hi = end;
    std::uint32_t next = kNoRope;
    for (int a = 0; a < 3; ++a) {
      const int f = exit_face[a];
      if (l.rope[f] == kNoRope) continue;
      const Real t = (Real(l.face[f]) - r.origin[a]) * r.inv_dir[a];
      if (t < hi) {  // NaN (the ray lies in the face) is never nearer
        hi = t;
        next = l.rope[f];
      }
    }
    if (l.count > 0 && (lo < hi || first) && leaf(blocks + l.first, l.count, lo, hi, t_max)) return;
    // Every leaf nearer than hi has been searched: a hit before it is the nearest.
    if (t_max <= hi || next == kNoRope) return;
    first = false;
    lo = hi;
    node = next;
  }
}

// Calls visit(prim) for each primitive of a leaf's blocks, in order; stops when it returns true.
template <class Visit>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE bool leaf_primitives(const SpatialLeaf* first, std::uint32_t count,
                                                            Visit&& visit) {
  for (std::uint32_t i = 0; i < count; ++i)
    for (int k = 0; k < kernel::kTriangleBlockWidth; ++k)
      if (first[i].prim[k] != kernel::kTriangleBlockEmpty && visit(first[i].prim[k])) return true;
  return false;
}

// The queries of the kd-tree and the octree, the same for both over their traverse_leaves(view,
// ray, t_min, t_max, leaf), which calls leaf(first, count, lo, hi, t_far) for each leaf the ray
// passes through, nearer leaves first, with the leaf's own interval [lo, hi].

// Visitor traversal (traversal.h): each primitive with its leaf's interval [lo, next_up(hi)).
template <class View, class Visitor>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void spatial_traverse(const View& view, const Ray& ray, Real t_min, Real& t_max,
                                                             Visitor& visit) {
  auto leaf = [&](const SpatialLeaf* first, std::uint32_t count, Real lo, Real hi, Real& t_far) {
    const Real leaf_hi = next_up(hi);
    return leaf_primitives(first, count, [&](std::uint32_t prim) { return visit(prim, lo, leaf_hi, t_far); });
  };
  traverse_leaves(view, ray, t_min, t_max, leaf);
}

// The nearest hit in (t_min, t_max): its id and hit, t = kInfinity when none. 
template <class View>
STRAHL_HOST_DEVICE inline void spatial_nearest(const View& view, const PrimitiveSet& prims, const Ray& ray,
                                               Real t_min, Real t_max, std::uint32_t& prim, kernel::TriangleHit& hit) {
  const kernel::TriangleBlockRay br = kernel::triangle_block_ray(ray, ray_shear_for(prims, ray.direction));
  auto leaf = [&](const SpatialLeaf* first, std::uint32_t count, Real, Real, Real& t_far) {
    kernel::blocks_nearest(first, count, prims, br, t_min, t_far, prim, hit);
    return false;
  };
  traverse_leaves(view, ray, t_min, t_max, leaf);
}

// Any hit in (t_min, t_max)? Stops at the first one.
template <class View>
STRAHL_HOST_DEVICE inline bool spatial_occluded(const View& view, const PrimitiveSet& prims, const Ray& ray,
                                                Real t_min, Real t_max) {
  const kernel::TriangleBlockRay br = kernel::triangle_block_ray(ray, ray_shear_for(prims, ray.direction));
  bool found = false;
  auto leaf = [&](const SpatialLeaf* first, std::uint32_t count, Real, Real, Real& t_far) {
    return found = kernel::blocks_any(first, count, prims, br, t_min, t_far);
  };
  traverse_leaves(view, ray, t_min, t_max, leaf);
  return found;
}

// ---- for building (host code) ----

// Ropes while building (both structures): which side of a plane at offset `plane` on `axis`
// holds the whole face f of a leaf whose box is `face` (RopedLeaf's faces), as the walk decides
// it for a ray leaving by that face: 0 below, 1 above, −1 when the plane cuts the face. On the
// face's own axis it is the side next to the face, a plane in the face itself counting as crossed
// on leaving by it. Elsewhere, where the face touches the plane, a ray leaving through that edge
// may count the plane crossed already: it then enters a leaf it only touches, which the walk
// passes over — never one beyond where the ray is.
int rope_side(int axis, float plane, int f, const float (&face)[6]);

// The faces and ropes of the root: ±∞, none.
void unbounded_faces(float (&face)[6], std::uint32_t (&rope)[6]);

// Appends the blocks of a leaf listing prims[0..count), filled in that order; returns how many.
std::uint32_t append_leaf(const PrimitiveSet& prims, const std::uint32_t* list, std::uint32_t count,
                          LargeArray<SpatialLeaf>& out);

// Primitives' bounds are grown by this fraction of the scene's largest coordinate magnitude:
// far above the rounding of hit points (~1e-16 relative), far below any feature worth splitting.
inline constexpr Real kBoundsPadding = Real(1e-9);

// The padding for a scene whose primitives' bounds (unpadded) are `scene`.
Real bounds_padding(const Bounds& scene);

Bounds padded(const Bounds& b, Real pad);

// The padded bounds of every primitive (in parallel) and of the whole scene, and the padding used.
struct PaddedBounds {
  LargeArray<Bounds> prims;
  Bounds scene;
  Real pad = 0;
};
PaddedBounds padded_primitive_bounds(const PrimitiveSet& prims);

// Closed overlap: boxes that only touch overlap.
bool overlaps(const Bounds& a, const Bounds& b);

// The bounds of the part of a primitive within `box` grown by `pad`, grown by `pad` themselves;
// empty when nothing of it is there. A primitive listed in a node by these bounds is listed in
// every leaf it comes within `pad` of. Triangles are clipped to the box (Sutherland–Hodgman), so
// one that crosses a corner of a box without touching it is not listed there ("perfect splits",
// Havran 2000); spheres and solids are bounded by their box's intersection with it.
Bounds clipped_bounds(const PrimitiveSet& prims, std::uint32_t prim, const Bounds& box, Real pad);

}  // namespace strahl
