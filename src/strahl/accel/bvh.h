#pragma once
// Bounding volume hierarchy: binned SAH build (in parallel) into one flat node array, the two
// children of a node side by side; traversal front to back with early exit.

#include <cstdint>
#include <vector>

#include "strahl/accel/primitive.h"
#include "strahl/accel/traversal.h"
#include "strahl/util/large_array.h"

namespace strahl {

struct BvhNode {
  Bounds bounds;
  std::uint32_t offset = 0;  // leaf: first entry in the primitive index array; inner: first child
                             // (the second child follows it)
  std::uint16_t count = 0;   // primitives in a leaf, 0 for inner nodes
  std::uint8_t axis = 0;     // inner: split axis, to visit the nearer child first
};

struct BvhView {
  const BvhNode* nodes = nullptr;
  const std::uint32_t* prims = nullptr;
};

// Its arrays are LargeArrays (util/large_array.h): fresh pages, 2 MiB ones for large trees.
struct Bvh {
  LargeArray<BvhNode> nodes;
  LargeArray<std::uint32_t> prims;
  BvhView view() const { return {nodes.data(), prims.data()}; }
};

// How the SAH weighs leaves: a leaf of n primitives costs ceil(n / leaf_block) primitive tests
// (leaf_block 4: the wide BVH tests four triangles at once, accel/triangle_block.h), a node visit
// costs traversal_cost of them; no leaf holds more than max_leaf primitives.
struct BvhBuildOptions {
  std::uint32_t leaf_block = 1;
  std::uint32_t max_leaf = 8;
  double traversal_cost = 1.0;
};

struct AccelBuildStats;
Bvh build_bvh(const PrimitiveSet& prims, AccelBuildStats* stats = nullptr, const BvhBuildOptions& options = {});
// The same over arbitrary boxes (primitive i has box i), e.g. the swept boxes of moving shapes;
// traverse() then reports indices into `boxes`. Primitives from first_costly on each cost a test
// of their own (as solids do in a scene's tree).
Bvh build_bvh(const std::vector<Bounds>& boxes, AccelBuildStats* stats = nullptr, const BvhBuildOptions& options = {},
              std::uint32_t first_costly = ~std::uint32_t(0));

// Calls visitor(prim, leaf_t_lo, leaf_t_hi, t_max) for every primitive in a leaf the ray reaches
// within (t_min, t_max), nearer leaves first; see traversal.h for the visitor contract.
template <class Visitor>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void traverse(const BvhView& bvh, const Ray& ray, Real t_min, Real& t_max, Visitor& visit) {
  if (bvh.nodes == nullptr) return;
  if (bvh.nodes[0].count > 0) {
    // A single leaf: its box test and the reciprocal direction would cost more than they save,
    // and its primitive order is the identity (nothing was partitioned), so no indirection.
    for (std::uint32_t prim = 0; prim < bvh.nodes[0].count; ++prim)
      if (visit(prim, -kInfinity, kInfinity, t_max)) return;
    return;
  }
  const Vec3 inv_dir = reciprocal(ray.direction);
  const int negative[3] = {inv_dir.x < 0, inv_dir.y < 0, inv_dir.z < 0};
  std::uint32_t stack[64];  // the build keeps the tree at most 64 deep (bvh.cpp, kMaxSahDepth)
  int top = 0;
  std::uint32_t node = 0;
  for (;;) {
    const BvhNode& n = bvh.nodes[node];
    if (hits(n.bounds, ray.origin, inv_dir, t_min, t_max)) {
      if (n.count > 0) {
        for (std::uint32_t i = n.offset; i < n.offset + n.count; ++i)
          if (visit(bvh.prims[i], -kInfinity, kInfinity, t_max)) return;
      } else {
        // Near child first: the first child lies on the low side of the split axis.
        const std::uint32_t first = n.offset, second = n.offset + 1;
        if (negative[n.axis]) { stack[top++] = first; node = second; }
        else { stack[top++] = second; node = first; }
        continue;
      }
    }
    if (top == 0) return;
    node = stack[--top];
  }
}

}  // namespace strahl
