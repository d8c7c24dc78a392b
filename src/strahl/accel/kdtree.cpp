#include "strahl/accel/kdtree.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "strahl/accel/build_stats.h"

namespace strahl {

namespace {

// SAH costs: a traversal step and one test of a block of four triangles (leaves are tested a block
// at a time, spatial.h, so a leaf of 1–4 primitives costs one test and the SAH counts leaves in
// blocks: leaves fill their blocks). Measured with the rope traversal on the bunny and the dragon
// (1 thread, interleaved runs, incoherent rays): 0.2 and 0.3 trace within a few per cent of each
// other, 0.45 5–15% slower, 0.8 and 1.2 20–40% slower with trees twice as big; 0.1 slower again.
// Counting primitives one by one instead (pre-blocks costs, 0.6 per triangle) built a tree twice
// as deep with 2.6× the references that traced ~30% slower. No bonus for empty children (pbrt,
// Wald & Havran use one): a bonus applied to any empty side favours shaving thin empty slices
// off a node over real splits (with pbrt's 0.5 the bunny rendered 2.7× slower here; 0.2 cost
// 5%), and the areas already reward cutting off empty space.
constexpr Real kTraversalCost = 1.0;
constexpr Real kIntersectCost = 0.2;
constexpr Real blocks(std::uint32_t n) {
  return Real((n + std::uint32_t(kernel::kTriangleBlockWidth) - 1) / std::uint32_t(kernel::kTriangleBlockWidth));
}
// A split that saves less than this fraction of the leaf's cost is a bad refine; pbrt tolerates
// three on a path, to see past a local minimum. Counting the nearly useless ones too keeps piles
// of overlapping primitives (each split duplicating almost all of them) from multiplying their
// references down to the depth limit for a gain of a few per cent.
constexpr Real kMinGain = 0.1;
constexpr int kMaxBadRefines = 3;
constexpr std::uint32_t kMaxIndex = (1u << 30) - 1;

// A primitive's bounds seen along one axis: where they start and end, or both at once when
// they are flat in that axis. At equal positions ends sort first.
enum class EventType : std::uint8_t { End, Planar, Start };

struct Event {
  Real pos;
  std::uint32_t prim;
  EventType type;
};

bool operator<(const Event& a, const Event& b) {
  if (a.pos != b.pos) return a.pos < b.pos;
  if (a.type != b.type) return a.type < b.type;
  return a.prim < b.prim;
}

using Events = std::array<LargeArray<Event>, 3>;

// Half the surface area of a box: SAH only compares ratios.
Real half_area(const Vec3& d) { return d.x * d.y + d.y * d.z + d.z * d.x; }

enum class Side : std::uint8_t { Both, Below, Above };

struct Split {
  Real cost = kInfinity;
  int axis = -1;
  Real pos = 0;
};

void set_component(Vec3& v, int axis, Real x) { (axis == 0 ? v.x : axis == 1 ? v.y : v.z) = x; }

void add_events(Events& events, std::uint32_t prim, const Bounds& b) {
  for (int axis = 0; axis < 3; ++axis) {
    LargeArray<Event>& e = events[std::size_t(axis)];
    if (b.lo[axis] == b.hi[axis]) {
      e.push_back({b.lo[axis], prim, EventType::Planar});
    } else {
      e.push_back({b.lo[axis], prim, EventType::Start});
      e.push_back({b.hi[axis], prim, EventType::End});
    }
  }
}

// The SAH sweep over each axis's sorted events: O(events).
Split best_split(const Bounds& box, const Events& events, std::uint32_t count) {
  Split best;
  const Vec3 d = box.hi - box.lo;
  const Real inv_area = Real(1) / half_area(d);
  for (int axis = 0; axis < 3; ++axis) {
    const LargeArray<Event>& e = events[std::size_t(axis)];
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    const Real cap = d[b] * d[c], girth = d[b] + d[c];
    const Real lo = box.lo[axis], hi = box.hi[axis];
    std::uint32_t below = 0, above = count;  // primitives starting before / ending after the plane
    for (std::size_t i = 0; i < e.size();) {
      const Real p = e[i].pos;
      std::uint32_t ends = 0, planars = 0, starts = 0;
      for (; i < e.size() && e[i].pos == p; ++i) {
        switch (e[i].type) {
          case EventType::End: ++ends; break;
          case EventType::Planar: ++planars; break;
          case EventType::Start: ++starts; break;
        }
      }
      above -= ends + planars;
      if (p > lo && p < hi) {
        // Primitives flat in the plane itself go to both sides (as the split does).
        const Real n_below = blocks(below + planars), n_above = blocks(above + planars);
        const Real area_below = cap + (p - lo) * girth, area_above = cap + (hi - p) * girth;
        const Real cost = kTraversalCost + kIntersectCost * (area_below * n_below + area_above * n_above) * inv_area;
        if (cost < best.cost) best = {cost, axis, p};
      }
      below += starts + planars;
    }
  }
  return best;
}

// A subtree, its nodes numbered from 0 (so that subtrees built in parallel can be joined).
struct Subtree {
  LargeArray<KdNode> nodes;
  std::vector<std::uint32_t> refs;
  std::size_t leaves = 0, max_depth = 0, references = 0;
};

// Appends `sub` to `out`, renumbering its child indices and reference ranges.
void append(Subtree& out, const Subtree& sub) {
  const std::size_t node_offset = out.nodes.size(), ref_offset = out.refs.size();
  if (node_offset + sub.nodes.size() > kMaxIndex || ref_offset + sub.refs.size() > 0xffffffffu)
    throw std::length_error("kd-tree: too many nodes");
  for (KdNode n : sub.nodes) {
    if (!n.is_leaf()) n.bits = n.axis() | std::uint32_t(n.above_child() + node_offset) << 2;
    else if (n.count() > 1) n.prims += std::uint32_t(ref_offset);
    out.nodes.push_back(n);
  }
  out.refs.insert(out.refs.end(), sub.refs.begin(), sub.refs.end());
  out.leaves += sub.leaves;
  out.max_depth = std::max(out.max_depth, sub.max_depth);
  out.references += sub.references;
}

// Per-thread working memory. A node uses it only before it recurses, so a thread may take up
// another subtree while waiting for its own children.
struct Scratch {
  std::vector<Side> side;  // per primitive
  std::vector<std::uint32_t> straddling;
  Events new_below, new_above;
};

constexpr std::uint32_t kParallelThreshold = 4096;  // smaller subtrees are built on one thread

struct Builder {
  const PrimitiveSet& prims;
  Real pad;
  Vec3 base;
  int max_depth;
  tbb::enumerable_thread_specific<Scratch> scratch;

  void make_leaf(Subtree& out, const Events& events, int depth) const {
    KdNode leaf{};
    std::uint32_t count = 0;
    const std::size_t first = out.refs.size();
    for (const Event& e : events[0]) {
      if (e.type == EventType::End) continue;
      out.refs.push_back(e.prim);
      ++count;
    }
    if (count > kMaxIndex) throw std::length_error("kd-tree: too many primitives in one leaf");
    if (count == 1) {
      leaf.prims = out.refs.back();
      out.refs.pop_back();
    } else {
      leaf.prims = std::uint32_t(first);
    }
    leaf.bits = 3u | (count << 2);
    out.nodes.push_back(leaf);
    ++out.leaves;
    out.references += count;
    out.max_depth = std::max(out.max_depth, std::size_t(depth) + 1);
  }

  void build(Subtree& out, const Bounds& box, Events events, std::uint32_t count, int depth, int bad_refines) {
    if (count <= 1 || depth >= max_depth) return make_leaf(out, events, depth);
    const Split split = best_split(box, events, count);
    const Real leaf_cost = kIntersectCost * blocks(count);
    if (split.cost >= (1 - kMinGain) * leaf_cost) ++bad_refines;
    if (split.axis < 0 || (split.cost > 4 * leaf_cost && count < 16) || bad_refines >= kMaxBadRefines)
      return make_leaf(out, events, depth);

    // The plane as the node stores it: a float offset from base, strictly inside the box.
    const int axis = split.axis;
    float offset = float(split.pos - base[axis]);
    Real plane = base[axis] + Real(offset);
    if (plane <= box.lo[axis]) {
      offset = std::nextafter(offset, std::numeric_limits<float>::infinity());
      plane = base[axis] + Real(offset);
    } else if (plane >= box.hi[axis]) {
      offset = std::nextafter(offset, -std::numeric_limits<float>::infinity());
      plane = base[axis] + Real(offset);
    }
    if (!(plane > box.lo[axis] && plane < box.hi[axis])) return make_leaf(out, events, depth);

    // Which side each primitive lies on, from its events along the axis: ending before the plane
    // (or on it), below; starting after it (or on it), above; otherwise both, straddling or flat
    // in the plane.
    Scratch& s = scratch.local();
    if (s.side.empty()) s.side.resize(prims.size());
    for (const Event& e : events[std::size_t(axis)])
      if (e.type != EventType::End) s.side[e.prim] = Side::Both;
    for (const Event& e : events[std::size_t(axis)]) {
      if (e.type == EventType::End && e.pos <= plane) s.side[e.prim] = Side::Below;
      if (e.type == EventType::Start && e.pos >= plane) s.side[e.prim] = Side::Above;
    }
    std::uint32_t n_below = 0, n_above = 0;
    s.straddling.clear();
    for (const Event& e : events[std::size_t(axis)]) {
      if (e.type == EventType::End) continue;
      const Side side = s.side[e.prim];
      if (side == Side::Both) s.straddling.push_back(e.prim);
      else if (side == Side::Below) ++n_below;
      else ++n_above;
    }
    Bounds box_below = box, box_above = box;
    set_component(box_below.hi, axis, plane);
    set_component(box_above.lo, axis, plane);

    // Straddling primitives are clipped to each child: new events, sorted, merged into the
    // children's lists (which keep the others' events in order): O(n) per node, O(n log n) in all.
    for (std::size_t k = 0; k < 3; ++k) {
      s.new_below[k].clear();
      s.new_above[k].clear();
    }
    for (const std::uint32_t p : s.straddling) {
      Bounds b = clipped_bounds(prims, p, box_below, pad), a = clipped_bounds(prims, p, box_above, pad);
      if (b.empty() && a.empty()) a = b = padded(primitive_bounds(prims, p), pad);  // rounding: keep it
      if (!b.empty()) add_events(s.new_below, p, b), ++n_below;
      if (!a.empty()) add_events(s.new_above, p, a), ++n_above;
    }
    Events below, above;
    const auto merge = [&](LargeArray<Event>& to, const LargeArray<Event>& old, Side keep,
                           LargeArray<Event>& added) {
      std::sort(added.begin(), added.end());
      to.reserve(added.size() + old.size() / 2);
      std::size_t j = 0;
      for (const Event& e : old) {
        if (s.side[e.prim] != keep) continue;
        for (; j < added.size() && added[j] < e; ++j) to.push_back(added[j]);
        to.push_back(e);
      }
      to.insert(to.end(), added.begin() + std::ptrdiff_t(j), added.end());
    };
    for (std::size_t k = 0; k < 3; ++k) {
      merge(below[k], events[k], Side::Below, s.new_below[k]);
      merge(above[k], events[k], Side::Above, s.new_above[k]);
      events[k] = {};  // this node's lists are no longer needed: free them before recursing
    }

    // The node, then the subtree below the plane, then the one above.
    const std::size_t at = out.nodes.size();
    out.nodes.push_back({});
    out.nodes[at].split = offset;
    if (count > kParallelThreshold) {
      Subtree sub_below, sub_above;
      tbb::parallel_invoke(
          [&] { build(sub_below, box_below, std::move(below), n_below, depth + 1, bad_refines); },
          [&] { build(sub_above, box_above, std::move(above), n_above, depth + 1, bad_refines); });
      append(out, sub_below);
      out.nodes[at].bits = std::uint32_t(axis) | std::uint32_t(out.nodes.size()) << 2;
      append(out, sub_above);
    } else {
      build(out, box_below, std::move(below), n_below, depth + 1, bad_refines);
      if (out.nodes.size() > kMaxIndex) throw std::length_error("kd-tree: too many nodes");
      out.nodes[at].bits = std::uint32_t(axis) | std::uint32_t(out.nodes.size()) << 2;
      build(out, box_above, std::move(above), n_above, depth + 1, bad_refines);
    }
  }
};

// Fills in every leaf's box and ropes (KdLeaf), walking down from the root with the box of the
// node at hand and the ropes of its faces.
struct Linker {
  const LargeArray<KdNode>& nodes;
  LargeArray<KdLeaf>& leaves;

  // The deepest node below `target` (beyond face f of a leaf with box `face`) whose box still
  // holds the whole face (rope_side, spatial.h).
  std::uint32_t push_down(std::uint32_t target, int f, const float (&face)[6]) const {
    if (target == kNoRope) return target;
    for (;;) {
      const KdNode& n = nodes[target];
      if (n.is_leaf()) return target;
      const int side = rope_side(int(n.axis()), n.split, f, face);
      if (side < 0) return target;
      target = side ? n.above_child() : target + 1;
    }
  }

  void link(std::uint32_t node, float (&face)[6], std::uint32_t (&rope)[6]) {
    const KdNode n = nodes[node];
    if (n.is_leaf()) {
      KdLeaf& leaf = leaves[n.prims];
      for (int f = 0; f < 6; ++f) {
        leaf.face[f] = face[f];
        leaf.rope[f] = push_down(rope[f], f, face);
      }
      return;
    }
    const int lower = 2 * int(n.axis()), upper = lower + 1;
    const std::uint32_t below = node + 1, above = n.above_child();
    const float saved_face[2] = {face[lower], face[upper]};
    const std::uint32_t saved_rope[2] = {rope[lower], rope[upper]};
    face[upper] = n.split;
    rope[upper] = above;
    link(below, face, rope);
    face[upper] = saved_face[1];
    rope[upper] = saved_rope[1];
    face[lower] = n.split;
    rope[lower] = below;
    link(above, face, rope);
    face[lower] = saved_face[0];
    rope[lower] = saved_rope[0];
  }
};

}  // namespace

KdTree build_kdtree(const PrimitiveSet& prims, AccelBuildStats* stats_out) {
  const auto start = std::chrono::steady_clock::now();
  const std::uint32_t n = prims.size();
  KdTree kd;
  AccelBuildStats stats;
  stats.primitives = n;
  if (n > 0) {
    PaddedBounds padded_bounds = padded_primitive_bounds(prims);
    LargeArray<Bounds>& bounds = padded_bounds.prims;
    const Real pad = padded_bounds.pad;
    kd.bounds = padded_bounds.scene;
    kd.base = kd.bounds.lo;

    Events events;
    tbb::parallel_for(0, 3, [&](int axis) {
      LargeArray<Event>& e = events[std::size_t(axis)];
      e.reserve(2 * std::size_t(n));
      for (std::uint32_t i = 0; i < n; ++i) {
        const Real lo = bounds[i].lo[axis], hi = bounds[i].hi[axis];
        if (lo == hi) {
          e.push_back({lo, i, EventType::Planar});
        } else {
          e.push_back({lo, i, EventType::Start});
          e.push_back({hi, i, EventType::End});
        }
      }
      tbb::parallel_sort(e.begin(), e.end());
    });

    // pbrt's depth limit, 8 + 1.3 log2 n, at most kKdMaxDepth.
    const int max_depth = std::min(kKdMaxDepth, int(std::lround(8 + 1.3 * std::log2(double(n)))));
    Builder builder{prims, pad, kd.base, max_depth, {}};
    Subtree tree;
    tree.nodes.reserve(2 * std::size_t(n));
    builder.build(tree, kd.bounds, std::move(events), n, 0, 0);
    kd.nodes = std::move(tree.nodes);
    kd.nodes.shrink_to_fit();
    // The leaves and their blocks, in node order (depth first: neighbouring leaves lie together).
    kd.leaves.reserve(tree.leaves);
    for (KdNode& node : kd.nodes) {
      if (!node.is_leaf()) continue;
      const std::uint32_t count = node.count();
      KdLeaf leaf{};
      leaf.first = std::uint32_t(kd.blocks.size());
      leaf.count = append_leaf(prims, count == 1 ? &node.prims : tree.refs.data() + node.prims, count, kd.blocks);
      node.prims = std::uint32_t(kd.leaves.size());
      node.bits = 3u;  // the count lives in the leaf
      kd.leaves.push_back(leaf);
    }
    kd.blocks.shrink_to_fit();
    float face[6];
    std::uint32_t rope[6];
    unbounded_faces(face, rope);
    Linker{kd.nodes, kd.leaves}.link(0, face, rope);
    stats.leaves = tree.leaves;
    stats.max_depth = tree.max_depth;
    stats.primitive_references = tree.references;
  }
  stats.nodes = kd.nodes.size();
  stats.bytes =
      kd.nodes.size() * sizeof(KdNode) + kd.leaves.size() * sizeof(KdLeaf) + kd.blocks.size() * sizeof(SpatialLeaf);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats_out) *stats_out = stats;
  return kd;
}

}  // namespace strahl
