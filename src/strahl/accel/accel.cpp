#include "strahl/accel/accel.h"

#include "strahl/accel/embree_range.h"
#include "strahl/util/number_syntax.h"

#include <chrono>
#include <cmath>
#include <utility>

namespace strahl {

namespace {
constexpr std::pair<AccelKind, std::string_view> kNames[] = {
    {AccelKind::Naive, "naive"},
    {AccelKind::Bvh, "bvh"},
    {AccelKind::KdTree, "kdtree"},
    {AccelKind::Octree, "octree"},
#if defined(STRAHL_HAVE_EMBREE)
    {AccelKind::Embree, "embree"},
#endif
};
}  // namespace

std::string_view accel_name(AccelKind kind) {
  for (const auto& [k, name] : kNames)
    if (k == kind) return name;
  return "?";
}

std::optional<AccelKind> accel_from_name(std::string_view name) {
  for (const auto& [k, n] : kNames)
    if (n == name) return k;
  return std::nullopt;
}

std::string accel_names() {
  std::string out;
  for (const auto& [k, name] : kNames) out += (out.empty() ? "" : ", ") + std::string(name);
  return out;
}

std::vector<AccelKind> accel_kinds() {
  std::vector<AccelKind> kinds;
  for (const auto& [k, name] : kNames) kinds.push_back(k);
  return kinds;
}

std::string embree_misfit(const PrimitiveSet& prims) {
  for (std::uint32_t i = 0; i < prims.size(); ++i) {
    const Bounds b = primitive_bounds(prims, i);
    const Real at = std::fmax(max_abs_component(b.lo), max_abs_component(b.hi));
    const Real size = max_component(b.hi - b.lo);
    if (at > kEmbreeMaxCoordinate || size < kEmbreeMinSize || size < kEmbreeMinRelativeSize * at)
      return "a primitive of size " + number::shortest(size) + " at " + number::shortest(at) +
             " (Embree computes in float: primitives from 1e-10 to 1e15 units within ±1e15, none smaller than 1e-5 "
             "of its distance from the origin)";
  }
  return {};
}

Accel build_accel(AccelKind kind, const PrimitiveSet& prims) {
  Accel a;
  a.kind = kind;
  const auto start = std::chrono::steady_clock::now();
  switch (kind) {
    case AccelKind::Naive: {
      a.stats.primitives = a.stats.primitive_references = prims.size();
      a.stats.nodes = a.stats.leaves = a.stats.max_depth = prims.size() > 0 ? 1 : 0;
      break;
    }
    case AccelKind::Bvh: a.bvh = build_wide_bvh(prims, &a.stats); break;
    case AccelKind::KdTree: a.kdtree = build_kdtree(prims, &a.stats); break;
    case AccelKind::Octree: a.octree = build_octree(prims, &a.stats); break;
#if defined(STRAHL_HAVE_EMBREE)
    // Solids have no Embree user geometry yet, and Embree computes in float (embree_range.h):
    // such scenes get the BVH, whose answers are the same as naive's.
    case AccelKind::Embree:
      if (prims.solid_count > 0 || !embree_misfit(prims).empty()) {
        a.kind = AccelKind::Bvh;
        a.bvh = build_wide_bvh(prims, &a.stats);
      } else {
        a.embree = build_embree(prims, &a.stats);
      }
      break;
#endif
  }
  if (is_sphere_leaf(a.view(prims))) a.sphere_quads = kernel::sphere_quads(prims.spheres, prims.sphere_count);
  a.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return a;
}

}  // namespace strahl
