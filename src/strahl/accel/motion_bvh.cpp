#include "strahl/accel/motion_bvh.h"

#include <cassert>

namespace strahl {

MotionBvhView MotionBvh::view() const {
  MotionBvhView v;
  if (segments == 0) return v;
  v.trees = trees.view();
  v.segments = segments;
  for (std::uint32_t k = 0; k < segments; ++k) v.first_node[k] = first_node[k];
  return v;
}

namespace {

constexpr std::uint64_t kMaxSegmentPrimitives = std::uint64_t(1) << 20;
constexpr std::uint64_t kFewSegmentPrimitives = 4096;

// The boxes of segment k of K into `boxes` (count of them; the caller's array, reused: fresh
// memory costs page faults).
void segment_boxes(std::uint32_t count, const SweptBox& box, std::uint32_t k, std::uint32_t segments,
                   std::vector<Bounds>& boxes) {
  const Real u0 = Real(k) / Real(segments), u1 = Real(k + 1) / Real(segments);
  boxes.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) boxes[i] = box(i, u0, u1);
}

// Σ of the boxes' surface areas over the K segments, divided by K.
double mean_swept_area(std::uint32_t count, const SweptBox& box, std::uint32_t segments) {
  double sum = 0;
  for (std::uint32_t k = 0; k < segments; ++k) {
    const Real u0 = Real(k) / Real(segments), u1 = Real(k + 1) / Real(segments);
    for (std::uint32_t i = 0; i < count; ++i) sum += double(surface_area(box(i, u0, u1)));
  }
  return sum / segments;
}

}  // namespace

MotionBvh build_motion_bvh(std::uint32_t count, const SweptBox& box, std::uint32_t segments, std::uint32_t first_costly) {
  MotionBvh out;
  if (count == 0) return out;
  assert(segments <= kMaxMotionSegments && (segments & (segments - 1)) == 0);
  std::uint32_t k_chosen = segments != 0 ? segments : 1;
  // A few cheap shapes are one leaf without a box (bvh.cpp), the same in every segment: K = 1.
  const bool one_cheap_leaf = first_costly >= count && count <= BvhBuildOptions{}.max_leaf;
  if (segments == 0 && !one_cheap_leaf) {
    out.swept_area[0] = mean_swept_area(count, box, 1);
    for (int i = 1; (1u << i) <= kMaxMotionSegments && (std::uint64_t(count) << i) <= kMaxSegmentPrimitives; ++i) {
      out.swept_area[i] = mean_swept_area(count, box, 1u << i);
      // A few shapes' trees cost next to nothing: they take any halving that cuts the area by a
      // twentieth (one large box shrinking slowly beside small fast ones, whose boxes halve).
      const double cut = (std::uint64_t(count) << i) <= kFewSegmentPrimitives ? 0.95 : 0.8;
      if (!(out.swept_area[i] <= cut * out.swept_area[i - 1])) break;
      k_chosen = 1u << i;
    }
  }
  out.segments = k_chosen;
  // One binary tree over the shapes where they are at mid-shutter; each segment gets a copy with
  // the boxes refitted to what the shapes sweep in it, collapsed into its wide tree. Children
  // follow their parent in the binary array (bvh.cpp), so a pass from the back sees a node's
  // children before the node. A tree of one leaf (a few shapes) stays one: no box test.
  std::vector<Bounds> boxes(count);
  for (std::uint32_t i = 0; i < count; ++i) boxes[i] = box(i, Real(0.5), Real(0.5));
  const Bvh tree = build_bvh(boxes, nullptr, {}, first_costly);
  out.trees.prims.assign(tree.prims.begin(), tree.prims.end());
  const bool one_leaf = tree.nodes[0].count > 0, costly = first_costly < count;
  if (one_leaf && !costly) out.trees.root_leaf_count = tree.nodes[0].count;
  LargeArray<BvhNode> refit;
  for (std::uint32_t k = 0; k < k_chosen; ++k) {
    segment_boxes(count, box, k, k_chosen, boxes);
    refit.assign(tree.nodes.begin(), tree.nodes.end());
    for (std::size_t i = refit.size(); i-- > 0;) {
      BvhNode& n = refit[i];
      Bounds b;
      if (n.count > 0) {
        for (std::uint32_t j = n.offset; j < n.offset + n.count; ++j) b = merge(b, boxes[out.trees.prims[j]]);
      } else {
        b = merge(refit[n.offset].bounds, refit[n.offset + 1].bounds);
      }
      n.bounds = b;
    }
    widen_extent(out.trees.extent, refit[0].bounds);
    if (one_leaf && costly) out.first_node[k] = append_wide_leaf_root(refit[0].bounds, refit[0].count, out.trees.nodes);
    else if (!one_leaf) out.first_node[k] = append_wide_nodes(refit.data(), out.trees.nodes);
  }
  return out;
}

MotionBvh build_motion_bvh(const std::vector<kernel::MovingSphere>& spheres,
                           const std::vector<kernel::MovingTriangle>& triangles,
                           const std::vector<kernel::MovingSolid>& solids,
                           const std::vector<kernel::MovingInstance>& instances, std::uint32_t segments) {
  const auto n = static_cast<std::uint32_t>(spheres.size());
  const auto m = n + static_cast<std::uint32_t>(triangles.size());
  const auto k = m + static_cast<std::uint32_t>(solids.size());
  return build_motion_bvh(
      k + static_cast<std::uint32_t>(instances.size()),
      [&](std::uint32_t i, Real u0, Real u1) {
        return i < n   ? kernel::swept_bounds(spheres[i], u0, u1)
               : i < m ? kernel::swept_bounds(triangles[i - n], u0, u1)
               : i < k ? kernel::swept_bounds(solids[i - m], u0, u1)
                       : kernel::swept_bounds(instances[i - k], u0, u1);
      },
      segments, m);
}

}  // namespace strahl
