#pragma once
// The interchangeable acceleration structures over a scene's bounded primitives (spheres, solids and
// triangles): the lecture's naive loop, a BVH (default), a kd-tree and an octree, and Embree
// where CMake found it (STRAHL_HAVE_EMBREE). Kernel code dispatches on AccelKind with a switch;
// each structure has one traversal (see traversal.h) that every query — nearest hit, any hit,
// shadow transmittance — runs through. Embree has no visitor traversal: the three queries call
// it directly (embree_accel.h), on the host only.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "strahl/accel/build_stats.h"
#include "strahl/accel/bvh.h"
#include "strahl/accel/kdtree.h"
#include "strahl/accel/naive.h"
#include "strahl/accel/octree.h"
#include "strahl/accel/wide_bvh.h"
#include "strahl/geometry/sphere_quad.h"
#if defined(STRAHL_HAVE_EMBREE)
#include "strahl/accel/embree_accel.h"
#endif

namespace strahl {

enum class AccelKind : std::uint8_t {
  Naive,
  Bvh,
  KdTree,
  Octree,
#if defined(STRAHL_HAVE_EMBREE)
  Embree,
#endif
};

std::string_view accel_name(AccelKind kind);
std::optional<AccelKind> accel_from_name(std::string_view name);
// "naive, bvh, kdtree, octree" — for messages and --help.
std::string accel_names();
// Every kind built into this binary, in the order of accel_names().
std::vector<AccelKind> accel_kinds();

// What kernels read: the kind and the plain-data view of the structure built.
struct AccelView {
  AccelKind kind = AccelKind::Bvh;
  PrimitiveSet prims;
  WideBvhView bvh;
  KdTreeView kdtree;
  OctreeView octree;
#if defined(STRAHL_HAVE_EMBREE)
  void* embree = nullptr;  // RTCScene (opaque here; see embree_accel.h)
#endif
  // The tree built is one leaf holding every primitive (tiny scenes: the lecture's five spheres):
  // the queries run the naive loop over them, the same search without the traversal's and the
  // blocks' bookkeeping.
  bool one_leaf = false;
  // That leaf holds spheres only: the same spheres four by four (geometry/sphere_quad.h), tested
  // four at a time by the one-leaf queries below; null otherwise.
  const kernel::SphereQuad* sphere_quads = nullptr;
};

// Owns whichever structure was built. It holds primitive indices, not pointers, so the scene that
// owns both may be moved or copied (an Embree scene is shared between copies, by reference count).
struct Accel {
  AccelKind kind = AccelKind::Bvh;
  WideBvh bvh;
  KdTree kdtree;
  Octree octree;
#if defined(STRAHL_HAVE_EMBREE)
  EmbreeAccel embree;
#endif
  AccelBuildStats stats;
  std::vector<kernel::SphereQuad> sphere_quads;  // the one leaf's spheres, where it holds only spheres

  AccelView view(const PrimitiveSet& prims) const {
    AccelView v;
    v.kind = kind;
    v.prims = prims;
    v.bvh = bvh.view();
    v.kdtree = kdtree.view();
    v.octree = octree.view();
#if defined(STRAHL_HAVE_EMBREE)
    v.embree = embree.scene();
#endif
    v.one_leaf = (kind == AccelKind::Bvh && bvh.root_leaf_count > 0) ||
                 (kind == AccelKind::KdTree && !kdtree.nodes.empty() && kdtree.nodes[0].is_leaf()) ||
                 (kind == AccelKind::Octree && !octree.nodes.empty() && octree.nodes[0].is_leaf());
    if (!sphere_quads.empty()) v.sphere_quads = sphere_quads.data();
    return v;
  }
};

Accel build_accel(AccelKind kind, const PrimitiveSet& prims);

template <class Visitor>
STRAHL_HOST_DEVICE inline void traverse(const AccelView& a, const Ray& ray, Real t_min, Real t_max, Visitor& visit) {
  if (a.one_leaf) return traverse(NaiveView{a.prims.size()}, ray, t_min, t_max, visit);
  switch (a.kind) {
    case AccelKind::Naive: traverse(NaiveView{a.prims.size()}, ray, t_min, t_max, visit); break;
    case AccelKind::Bvh: traverse(a.bvh, ray, t_min, t_max, visit); break;
    case AccelKind::KdTree: traverse(a.kdtree, ray, t_min, t_max, visit); break;
    case AccelKind::Octree: traverse(a.octree, ray, t_min, t_max, visit); break;
#if defined(STRAHL_HAVE_EMBREE)
    // Embree has no visitor traversal; the queries below call it directly. Any other visitor
    // (and device code) gets the naive loop: slow, but the same answers.
    case AccelKind::Embree: traverse(NaiveView{a.prims.size()}, ray, t_min, t_max, visit); break;
#endif
  }
}

// ---- the queries, as visitors ----

// Nearest hit: primitive and t (and barycentrics for triangles).
struct NearestHit {
  std::uint32_t prim = 0;
  kernel::TriangleHit hit;  // t = kInfinity: none
};

// The structure is one leaf of spheres only (the lecture's scenes): the queries below run the
// naive loop's tests in its order, without the visitor's dispatch on the primitive's kind. The
// scene queries (render/intersect_scene.h) call these loops directly, without the call and the
// dispatch on the structure's kind.
STRAHL_HOST_DEVICE inline bool is_sphere_leaf(const AccelView& a) {
  return a.one_leaf && a.prims.size() == a.prims.sphere_count;
}

STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE NearestHit sphere_leaf_nearest(const AccelView& a, const Ray& ray, Real t_min,
                                                                      Real t_max) {
  const PrimitiveSet& p = a.prims;
  NearestHit result;
  Real t_far = t_max;
  if (a.sphere_quads != nullptr) {
    const std::uint32_t quads = kernel::sphere_quad_count(p.sphere_count);
    for (std::uint32_t j = 0; j < quads; ++j) {
      const int lane = kernel::intersect_nearest(a.sphere_quads[j], ray, t_min, t_far, t_far);
      if (lane >= 0) result.prim = j * kernel::kSphereQuadWidth + std::uint32_t(lane);
    }
    if (t_far < t_max) result.hit = {t_far, 0, 0};
    return result;
  }
  for (std::uint32_t i = 0; i < p.sphere_count; ++i) {
    const Real t = kernel::intersect(p.spheres[i], ray, t_min, t_far);
    if (t < t_far) {
      t_far = t;
      result.prim = i;
      result.hit = {t, 0, 0};
    }
  }
  return result;
}

STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE bool sphere_leaf_occluded(const AccelView& a, const Ray& ray, Real t_min,
                                                                 Real t_max) {
  const PrimitiveSet& p = a.prims;
  if (a.sphere_quads != nullptr) {
    const std::uint32_t quads = kernel::sphere_quad_count(p.sphere_count);
    for (std::uint32_t j = 0; j < quads; ++j)
      if (kernel::intersect_any(a.sphere_quads[j], ray, t_min, t_max)) return true;
    return false;
  }
  for (std::uint32_t i = 0; i < p.sphere_count; ++i)
    if (kernel::intersect(p.spheres[i], ray, t_min, t_max) < kInfinity) return true;
  return false;
}

STRAHL_HOST_DEVICE inline NearestHit nearest_hit(const AccelView& a, const Ray& ray, Real t_min, Real t_max) {
#if defined(STRAHL_HAVE_EMBREE) && !defined(__CUDACC__)
  if (a.kind == AccelKind::Embree) return embree_nearest_hit(a, ray, t_min, t_max);
#endif
  NearestHit result;
  if (a.kind == AccelKind::Bvh && !a.one_leaf) {  // leaf copies: no visitor, no indirection
    wide_bvh_nearest(a.bvh, a.prims, ray, t_min, t_max, result.prim, result.hit);
    return result;
  }
  if (a.kind == AccelKind::KdTree && !a.one_leaf) {  // the same, with each leaf's interval unused
    spatial_nearest(a.kdtree, a.prims, ray, t_min, t_max, result.prim, result.hit);
    return result;
  }
  if (a.kind == AccelKind::Octree && !a.one_leaf) {
    spatial_nearest(a.octree, a.prims, ray, t_min, t_max, result.prim, result.hit);
    return result;
  }
  if (is_sphere_leaf(a)) return sphere_leaf_nearest(a, ray, t_min, t_max);
  const kernel::RayShear shear = ray_shear_for(a.prims, ray.direction);
  auto visit = [&](std::uint32_t prim, Real, Real, Real& t_far) {
    const kernel::TriangleHit h = intersect_primitive(a.prims, prim, ray, shear, t_min, t_far);
    if (h.t < t_far) {
      t_far = h.t;
      result.prim = prim;
      result.hit = h;
    }
    return false;
  };
  traverse(a, ray, t_min, t_max, visit);
  return result;
}

// Any hit in (t_min, t_max)? Stops at the first one found.
STRAHL_HOST_DEVICE inline bool occluded(const AccelView& a, const Ray& ray, Real t_min, Real t_max) {
#if defined(STRAHL_HAVE_EMBREE) && !defined(__CUDACC__)
  if (a.kind == AccelKind::Embree) return embree_occluded(a, ray, t_min, t_max);
#endif
  if (!a.one_leaf) {
    if (a.kind == AccelKind::Bvh) return wide_bvh_occluded(a.bvh, a.prims, ray, t_min, t_max);
    if (a.kind == AccelKind::KdTree) return spatial_occluded(a.kdtree, a.prims, ray, t_min, t_max);
    if (a.kind == AccelKind::Octree) return spatial_occluded(a.octree, a.prims, ray, t_min, t_max);
  }
  if (is_sphere_leaf(a)) return sphere_leaf_occluded(a, ray, t_min, t_max);
  bool found = false;
  const kernel::RayShear shear = ray_shear_for(a.prims, ray.direction);
  auto visit = [&](std::uint32_t prim, Real, Real, Real& t_far) {
    found = a.prims.is_triangle(prim) ? intersect_primitive(a.prims, prim, ray, shear, t_min, t_far).t < kInfinity
                                      : hits_other(a.prims, prim, ray, t_min, t_far);
    return found;
  };
  traverse(a, ray, t_min, t_max, visit);
  return found;
}

// Every surface crossing in (t_min, t_max): calls cross(prim, crossings) and stops when it returns
// true. Crossings are counted only inside the reporting leaf's interval, so a primitive listed in
// several leaves is counted once.
template <class Cross>
STRAHL_HOST_DEVICE inline void for_each_crossing(const AccelView& a, const Ray& ray, Real t_min, Real t_max,
                                                 Cross& cross) {
#if defined(STRAHL_HAVE_EMBREE) && !defined(__CUDACC__)
  if (a.kind == AccelKind::Embree) {
    const EmbreeCrossFn call = [](void* state, std::uint32_t prim, int n) {
      return bool((*static_cast<Cross*>(state))(prim, n));
    };
    embree_for_each_crossing(a, ray, t_min, t_max, call, const_cast<void*>(static_cast<const void*>(&cross)));
    return;
  }
#endif
  const kernel::RayShear shear = ray_shear_for(a.prims, ray.direction);
  auto visit = [&](std::uint32_t prim, Real leaf_lo, Real leaf_hi, Real& t_far) {
    const Real lo = leaf_lo > t_min ? leaf_lo : t_min;
    const Real hi = leaf_hi < t_far ? leaf_hi : t_far;
    if (!(lo < hi)) return false;
    const int n = primitive_crossings(a.prims, prim, ray, shear, lo, hi);
    return n > 0 && cross(prim, n);
  };
  traverse(a, ray, t_min, t_max, visit);
}

}  // namespace strahl
