#pragma once
// The solids (box, cylinder/cone, disk, torus, quadric, implicit, and spheres and CSG trees) as
// one kind of primitive: a small handle (kind, index into the array of that kind, material).
// This file holds the handle, the arrays it indexes and what dispatches on the kinds that are
// shapes of their own ("leaves": every kind but Csg) with a switch — crossings along a ray,
// normal, inside test. geometry/csg.h combines leaves; geometry/solid.h dispatches over both.
// Kernel code: plain data, no virtual calls, no allocation.
//
// Implicit surfaces note the steepest gradient their root finding met (for the end-of-render
// warning) in an ImplicitTally per object, raised with an atomic maximum.

#include <atomic>
#include <cstdint>
#include <cstring>

#include "strahl/geometry/box.h"
#include "strahl/geometry/csg_program.h"
#include "strahl/geometry/cone.h"
#include "strahl/geometry/disk.h"
#include "strahl/geometry/implicit.h"
#include "strahl/geometry/placement.h"
#include "strahl/geometry/quadric.h"
#include "strahl/geometry/sphere.h"
#include "strahl/geometry/torus.h"
#include "strahl/math/bounds.h"

namespace strahl::kernel {

// Sphere: a sphere as a CSG operand or with a transform (plain top-level spheres have their own
// primitive ids); Csg: a CSG tree (geometry/csg.h) over other solids, its "leaves"; Placed: a
// shape of one of the other kinds but Csg, with a transform (geometry/placement.h).
enum class SolidKind : std::uint8_t { Box, Cone, Disk, Torus, Quadric, Implicit, Sphere, Csg, Placed };

struct Solid {
  SolidKind kind = SolidKind::Box;
  std::uint32_t index = 0;     // into the array of its kind
  std::uint32_t material = 0;
};

// A CSG tree's leaf (geometry/csg.h): its handle and, where a box test is cheaper than the leaf's
// own crossings (cones, tori, placed shapes), a box around it, enlarged by a millionth of its
// size: a ray range that misses the box has no crossing of the leaf and is outside it. A tree's
// entries after its leaves (Csg::leaf_count) hold only the boxes of groups of operands, which the
// program's Skips name (geometry/csg_program.h).
struct CsgLeaf {
  Solid solid;
  std::uint32_t boxed = 0;  // `box` holds the box
  Bounds box;
};

// What the root finding of one implicit surface met over a whole render (all threads).
struct ImplicitTally {
  std::uint64_t max_gradient_bits = 0;  // a non-negative double's bits: ordered as integers
  std::uint64_t exhausted = 0;
};

STRAHL_HOST_DEVICE inline void tally(ImplicitTally& t, const ImplicitStats& s) {
  if (s.max_gradient > 0) {
    std::uint64_t bits;
    std::memcpy(&bits, &s.max_gradient, sizeof bits);
#if defined(__CUDA_ARCH__)
    atomicMax(reinterpret_cast<unsigned long long*>(&t.max_gradient_bits), (unsigned long long)bits);
#else
    std::atomic_ref<std::uint64_t> m(t.max_gradient_bits);
    std::uint64_t seen = m.load(std::memory_order_relaxed);
    while (bits > seen && !m.compare_exchange_weak(seen, bits, std::memory_order_relaxed)) {
    }
#endif
  }
  if (s.exhausted > 0) {
#if defined(__CUDA_ARCH__)
    atomicAdd(reinterpret_cast<unsigned long long*>(&t.exhausted), (unsigned long long)s.exhausted);
#else
    std::atomic_ref<std::uint64_t>(t.exhausted).fetch_add(s.exhausted, std::memory_order_relaxed);
#endif
  }
}

inline Real max_gradient_of(const ImplicitTally& t) {
  Real g;
  std::memcpy(&g, &t.max_gradient_bits, sizeof g);
  return g;
}

struct PlacedSolid;

// The arrays the handles index.
struct SolidArrays {
  const Box* boxes = nullptr;
  const Cone* cones = nullptr;
  const Disk* disks = nullptr;
  const Torus* tori = nullptr;
  const Quadric* quadrics = nullptr;
  const Implicit* implicits = nullptr;
  ImplicitTally* tallies = nullptr;  // one per implicit
  const Sphere* spheres = nullptr;   // CSG operands only
  const Csg* csgs = nullptr;
  const CsgInstruction* csg_code = nullptr;  // every tree's program, one after the other
  const CsgLeaf* csg_leaves = nullptr;       // every tree's leaves, one after the other
  const PlacedSolid* placed = nullptr;
};

// A shape with a transform; bounds in world space (the transformed object bounds' box).
struct PlacedSolid {
  Placement to_object;
  Solid shape;  // in object space; never Csg or Placed
  Vec3 lo, hi;
};

// The kind of shape a handle stands for (a placed one's own).
STRAHL_HOST_DEVICE inline SolidKind shape_kind(const SolidArrays& a, const Solid& s) {
  return s.kind == SolidKind::Placed ? a.placed[s.index].shape.kind : s.kind;
}

// Whether the solid has an inside (its crossings alternate between entering and leaving).
STRAHL_HOST_DEVICE inline bool closed(const SolidArrays& a, const Solid& handle) {
  const Solid& s = handle.kind == SolidKind::Placed ? a.placed[handle.index].shape : handle;
  switch (s.kind) {
    case SolidKind::Cone: return !a.cones[s.index].open;
    case SolidKind::Disk: return false;
    case SolidKind::Quadric: return !a.quadrics[s.index].clipped;
    default: return true;  // Box, Torus, Implicit, Sphere, Csg
  }
}

// Bounds (host: building the structures). An unclipped quadric has none (infinite).
inline Bounds bounds(const SolidArrays& a, const Solid& s) {
  Bounds b;
  switch (s.kind) {
    case SolidKind::Box: b.extend(a.boxes[s.index].lo); b.extend(a.boxes[s.index].hi); break;
    case SolidKind::Cone: {
      const Cone& c = a.cones[s.index];
      const Vec3 cap = c.base + c.axis * c.height;
      // A disk of radius r around axis w extends r·√(1 − w_i²) along axis i.
      const Vec3 w = c.axis;
      const Vec3 e(std::sqrt(std::fmax(0.0, 1 - w.x * w.x)), std::sqrt(std::fmax(0.0, 1 - w.y * w.y)),
                   std::sqrt(std::fmax(0.0, 1 - w.z * w.z)));
      b.extend(c.base - e * c.base_radius);
      b.extend(c.base + e * c.base_radius);
      b.extend(cap - e * c.cap_radius);
      b.extend(cap + e * c.cap_radius);
      break;
    }
    case SolidKind::Disk: {
      const Disk& d = a.disks[s.index];
      const Vec3 w = d.normal;
      const Vec3 e(std::sqrt(std::fmax(0.0, 1 - w.x * w.x)), std::sqrt(std::fmax(0.0, 1 - w.y * w.y)),
                   std::sqrt(std::fmax(0.0, 1 - w.z * w.z)));
      b.extend(d.center - e * d.radius);
      b.extend(d.center + e * d.radius);
      break;
    }
    case SolidKind::Torus: {
      const Torus& t = a.tori[s.index];
      const Vec3 w = t.axis;
      const Vec3 e(std::sqrt(std::fmax(0.0, 1 - w.x * w.x)), std::sqrt(std::fmax(0.0, 1 - w.y * w.y)),
                   std::sqrt(std::fmax(0.0, 1 - w.z * w.z)));
      b.extend(t.center - e * t.major - Vec3(t.minor));
      b.extend(t.center + e * t.major + Vec3(t.minor));
      break;
    }
    case SolidKind::Quadric: {
      const Quadric& q = a.quadrics[s.index];
      if (q.clipped) {
        b.extend(q.lo);
        b.extend(q.hi);
      } else {
        b.extend(Vec3(-kInfinity));
        b.extend(Vec3(kInfinity));
      }
      break;
    }
    case SolidKind::Sphere: {
      const Sphere& sp = a.spheres[s.index];
      b.extend(sp.center - Vec3(sp.radius));
      b.extend(sp.center + Vec3(sp.radius));
      break;
    }
    case SolidKind::Csg: b.lo = a.csgs[s.index].lo; b.hi = a.csgs[s.index].hi; break;
    case SolidKind::Placed: b.lo = a.placed[s.index].lo; b.hi = a.placed[s.index].hi; break;
    case SolidKind::Implicit: {
      const Implicit& m = a.implicits[s.index];
      if (m.bound == ImplicitBound::Sphere) {
        b.extend(m.center - Vec3(m.radius));
        b.extend(m.center + Vec3(m.radius));
      } else {
        b.extend(m.lo);
        b.extend(m.hi);
      }
      break;
    }
  }
  return b;
}

// The crossings of a shape's surface with the whole line, sorted (every shape kind but Implicit,
// whose root finding works over a range: for_each_leaf_crossing).
STRAHL_HOST_DEVICE inline void shape_line_crossings(const SolidArrays& a, const Solid& s, const Ray& ray,
                                                    CrossingList& list) {
  switch (s.kind) {
    case SolidKind::Box: line_crossings(a.boxes[s.index], ray, list); break;
    case SolidKind::Cone: line_crossings(a.cones[s.index], ray, list); break;
    case SolidKind::Disk: line_crossings(a.disks[s.index], ray, list); break;
    case SolidKind::Torus: line_crossings(a.tori[s.index], ray, list); break;
    case SolidKind::Quadric: line_crossings(a.quadrics[s.index], ray, list); break;
    case SolidKind::Sphere: line_crossings(a.spheres[s.index], ray, list); break;
    case SolidKind::Implicit:
    case SolidKind::Csg:
    case SolidKind::Placed: break;
  }
}

// The same for any leaf (a placed shape: in its object space, where t is the same).
STRAHL_HOST_DEVICE inline void leaf_line_crossings(const SolidArrays& a, const Solid& s, const Ray& ray,
                                                   CrossingList& list) {
  if (s.kind == SolidKind::Placed) {
    const PlacedSolid& x = a.placed[s.index];
    shape_line_crossings(a, x.shape, object_ray(x.to_object, ray), list);
  } else {
    shape_line_crossings(a, s, ray, list);
  }
}

// Every crossing of a leaf's surface in (t_min, t_max), front to back: calls visit(const
// SolidCrossing&), which returns true to stop.
template <class Visit>
STRAHL_HOST_DEVICE inline void for_each_leaf_crossing(const SolidArrays& a, const Solid& leaf, const Ray& world_ray,
                                                      Real t_min, Real t_max, Visit&& visit) {
  const bool placed = leaf.kind == SolidKind::Placed;
  const Solid& s = placed ? a.placed[leaf.index].shape : leaf;
  const Ray ray = placed ? object_ray(a.placed[leaf.index].to_object, world_ray) : world_ray;
  if (s.kind == SolidKind::Implicit) {
    ImplicitStats stats;
    for_each_implicit_crossing(a.implicits[s.index], ray, t_min, t_max, stats, [&](const ImplicitCrossing& c) {
      return visit(SolidCrossing{c.t, std::uint32_t(c.on_bound ? 1 : 0), c.entering});
    });
    if (a.tallies != nullptr) tally(a.tallies[s.index], stats);
    return;
  }
  CrossingList list;
  shape_line_crossings(a, s, ray, list);
  for (int i = 0; i < list.n; ++i)
    if (list.c[i].t > t_min && list.c[i].t < t_max && visit(list.c[i])) return;
}

// Any crossing of a leaf's surface in (t_min, t_max)? An implicit surface answers without
// refining a root (any_crossing()); every other shape by its crossings.
STRAHL_HOST_DEVICE inline bool leaf_any_crossing(const SolidArrays& a, const Solid& leaf, const Ray& world_ray,
                                                 Real t_min, Real t_max) {
  const bool placed = leaf.kind == SolidKind::Placed;
  const Solid& s = placed ? a.placed[leaf.index].shape : leaf;
  if (s.kind == SolidKind::Implicit) {
    const Ray ray = placed ? object_ray(a.placed[leaf.index].to_object, world_ray) : world_ray;
    ImplicitStats stats;
    const bool hit = any_crossing(a.implicits[s.index], ray, t_min, t_max, stats);
    if (a.tallies != nullptr) tally(a.tallies[s.index], stats);
    return hit;
  }
  bool hit = false;
  for_each_leaf_crossing(a, leaf, world_ray, t_min, t_max, [&](const SolidCrossing&) { return hit = true; });
  return hit;
}

// Outward unit normal at a surface point of part `part`.
STRAHL_HOST_DEVICE inline Vec3 shape_normal_at(const SolidArrays& a, const Solid& s, int part, const Vec3& p) {
  switch (s.kind) {
    case SolidKind::Box: return normal_at(a.boxes[s.index], part);
    case SolidKind::Cone: return normal_at(a.cones[s.index], part, p);
    case SolidKind::Disk: return a.disks[s.index].normal;
    case SolidKind::Torus: return normal_at(a.tori[s.index], p);
    case SolidKind::Quadric: return normal_at(a.quadrics[s.index], p);
    case SolidKind::Implicit: return normal_at(a.implicits[s.index], p, part == 1);
    case SolidKind::Sphere: return normal_at(a.spheres[s.index], p);
    case SolidKind::Csg:
    case SolidKind::Placed: break;
  }
  return Vec3(0, 1, 0);
}

// Is p inside the solid? (false for open surfaces: disks, open cones, clipped quadrics are not
// solids; a clipped quadric answers for its clipped region.)
STRAHL_HOST_DEVICE inline bool shape_inside(const SolidArrays& a, const Solid& s, const Vec3& p) {
  switch (s.kind) {
    case SolidKind::Box: return inside(a.boxes[s.index], p);
    case SolidKind::Cone: return !a.cones[s.index].open && inside(a.cones[s.index], p);
    case SolidKind::Disk: return false;
    case SolidKind::Torus: return inside(a.tori[s.index], p);
    case SolidKind::Quadric: return inside(a.quadrics[s.index], p);
    case SolidKind::Implicit: return inside(a.implicits[s.index], p);
    case SolidKind::Sphere: return inside(a.spheres[s.index], p);
    case SolidKind::Csg:
    case SolidKind::Placed: break;
  }
  return false;
}

// Any leaf's normal and inside test: a placed shape's in its object space, the normal brought
// back by the inverse transpose.
STRAHL_HOST_DEVICE inline Vec3 leaf_normal_at(const SolidArrays& a, const Solid& s, int part, const Vec3& p) {
  if (s.kind != SolidKind::Placed) return shape_normal_at(a, s, part, p);
  const PlacedSolid& x = a.placed[s.index];
  return world_normal(x.to_object, shape_normal_at(a, x.shape, part, object_point(x.to_object, p)));
}
STRAHL_HOST_DEVICE inline bool leaf_inside(const SolidArrays& a, const Solid& s, const Vec3& p) {
  if (s.kind != SolidKind::Placed) return shape_inside(a, s, p);
  const PlacedSolid& x = a.placed[s.index];
  return shape_inside(a, x.shape, object_point(x.to_object, p));
}

}  // namespace strahl::kernel
