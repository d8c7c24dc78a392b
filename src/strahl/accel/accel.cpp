#include "strahl/accel/accel.h"

#include <chrono>
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
    // Solids have no Embree user geometry yet: such scenes get the BVH, whose answers are the same.
    case AccelKind::Embree:
      if (prims.solid_count > 0) {
        a.kind = AccelKind::Bvh;
        a.bvh = build_wide_bvh(prims, &a.stats);
      } else {
        a.embree = build_embree(prims, &a.stats);
      }
      break;
#endif
  }
  a.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return a;
}

}  // namespace strahl
