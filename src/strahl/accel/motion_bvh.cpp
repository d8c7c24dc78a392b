#include "strahl/accel/motion_bvh.h"

#include <cassert>

namespace strahl {

MotionBvhView MotionBvh::view() const {
  MotionBvhView v;
  if (segments == 0) return v;
  v.nodes = nodes.data();
  v.prims = prims.data();
  v.segments = segments;
  for (std::uint32_t k = 0; k < segments; ++k) {
    v.first_node[k] = first_node[k];
    v.first_prim[k] = first_prim[k];
  }
  return v;
}

namespace {

constexpr std::uint64_t kMaxSegmentPrimitives = std::uint64_t(1) << 22;

std::vector<Bounds> segment_boxes(std::uint32_t count, const SweptBox& box, std::uint32_t k, std::uint32_t segments) {
  const Real u0 = Real(k) / Real(segments), u1 = Real(k + 1) / Real(segments);
  std::vector<Bounds> boxes(count);
  for (std::uint32_t i = 0; i < count; ++i) boxes[i] = box(i, u0, u1);
  return boxes;
}

// Σ of the boxes' surface areas over the K segments, divided by K.
double mean_swept_area(std::uint32_t count, const SweptBox& box, std::uint32_t segments) {
  double sum = 0;
  for (std::uint32_t k = 0; k < segments; ++k)
    for (const Bounds& b : segment_boxes(count, box, k, segments)) sum += double(surface_area(b));
  return sum / segments;
}

}  // namespace

MotionBvh build_motion_bvh(std::uint32_t count, const SweptBox& box, std::uint32_t segments) {
  MotionBvh out;
  if (count == 0) return out;
  assert(segments <= kMaxMotionSegments && (segments & (segments - 1)) == 0);
  std::uint32_t k_chosen = segments != 0 ? segments : 1;
  if (segments == 0) {
    out.swept_area[0] = mean_swept_area(count, box, 1);
    for (int i = 1; (1u << i) <= kMaxMotionSegments && (std::uint64_t(count) << i) <= kMaxSegmentPrimitives; ++i) {
      out.swept_area[i] = mean_swept_area(count, box, 1u << i);
      if (!(out.swept_area[i] <= 0.8 * out.swept_area[i - 1])) break;
      k_chosen = 1u << i;
    }
  }
  out.segments = k_chosen;
  for (std::uint32_t k = 0; k < k_chosen; ++k) {
    const Bvh tree = build_bvh(segment_boxes(count, box, k, k_chosen));
    out.first_node[k] = static_cast<std::uint32_t>(out.nodes.size());
    out.first_prim[k] = static_cast<std::uint32_t>(out.prims.size());
    out.nodes.insert(out.nodes.end(), tree.nodes.begin(), tree.nodes.end());
    out.prims.insert(out.prims.end(), tree.prims.begin(), tree.prims.end());
  }
  return out;
}

}  // namespace strahl
