#pragma once
// Constructive solid geometry over crossing intervals. Every operand answers, along a ray's range
// (t_min, t_max), whether the range starts inside it and its surface crossings front to back, each
// with the side it leaves the ray on ("inside after", SolidCrossing::entering): a list. The tree's
// postfix program (geometry/csg_program.h) combines lists on a fixed-size stack, so it runs
// unchanged on a GPU: no allocation, no recursion, no virtual calls.
//
// Which surfaces a node keeps (POV-Ray's rules, on crossings):
//   union         every crossing of every operand (inner surfaces stay visible);
//   merge         a crossing where the union's side changes (no inner surfaces);
//   intersection  a crossing where the side of "inside all" changes, and an operand's inner
//                 surface (a union's) where the other operand is inside;
//   inverse       every crossing, sides swapped, its normal flipped;
//   difference    A ∩ inverse(B) (compiled so): B's surface inside A, normal flipped.
// Coincident surfaces: crossings at exactly the same t are taken as one group, the sides of the
// operands before and after the group decide, and at most one crossing stands for a change of
// side. So A − A and A ∩ B with A, B touching are empty, A ∩ A = A, and two boxes sharing a
// face merge without a crossing there: no sparkles from a coin toss of rounding. (Surfaces that
// coincide only up to rounding are ordinary separate crossings, as in POV-Ray.)
//
// A list holds at most kMaxCsgCrossings crossings. When one would overflow (an implicit surface
// with many crossings, a union of many operands along one ray) it keeps those before the first
// crossing it cannot hold and says so in `valid_until`; the caller evaluates the tree again
// from there (for_each_csg_crossing), at most kMaxCsgRounds times per query.
//
// A crossing's part: leaf index << 16 | kCsgFlip if the normal is flipped | the leaf's own part.

#include <cmath>
#include <cstdint>

#include "strahl/geometry/solid_leaf.h"

namespace strahl::kernel {

inline constexpr int kMaxCsgCrossings = 32;
inline constexpr int kMaxCsgRounds = 64;
inline constexpr std::uint32_t kCsgFlip = 0x8000;

STRAHL_HOST_DEVICE inline std::uint32_t csg_part(std::uint32_t leaf, std::uint32_t part) {
  return (leaf << 16) | (part & 0x7fff);
}

struct CsgList {
  SolidCrossing c[kMaxCsgCrossings];
  int n = 0;
  bool start_inside = false;
  Real valid_until = kInfinity;  // the list is complete for t < valid_until

  // Appends a crossing (t not below the last); false when the list is full: it then ends before t.
  STRAHL_HOST_DEVICE bool add(Real t, std::uint32_t part, bool inside_after) {
    if (!(t < valid_until)) return false;
    if (n == kMaxCsgCrossings) {
      valid_until = t;
      while (n > 0 && c[n - 1].t >= t) --n;
      return false;
    }
    c[n++] = {t, part, inside_after};
    return true;
  }
};

// A leaf's list over (t_min, t_max). Crossings that repeat the current side (a tangent ray, a
// root finder's double report) are dropped, so sides alternate.
STRAHL_HOST_DEVICE inline void csg_leaf_list(const SolidArrays& a, const Solid& s, std::uint32_t leaf, const Ray& ray,
                                             Real t_min, Real t_max, CsgList& out) {
  out.n = 0;
  out.valid_until = kInfinity;
  bool side = false;
  const SolidKind kind = shape_kind(a, s);
  if (kind == SolidKind::Implicit) {
    bool known = false;
    for_each_leaf_crossing(a, s, ray, t_min, t_max, [&](const SolidCrossing& c) {
      if (!known) {
        known = true;
        side = out.start_inside = !c.entering;
      }
      if (c.entering == side) return false;
      side = c.entering;
      return !out.add(c.t, csg_part(leaf, c.part), side);
    });
    // No crossing in the range: all of it on one side (outside, past a bounded solid's far end).
    if (!known) out.start_inside = std::isfinite(t_max) && leaf_inside(a, s, ray.at((t_min + t_max) / 2));
    return;
  }
  CrossingList list;
  leaf_line_crossings(a, s, ray, list);
  // The side at t_min: after the last crossing up to it, else before the first after it.
  int i = 0;
  while (i < list.n && !(list.c[i].t > t_min)) ++i;
  if (i > 0) side = list.c[i - 1].entering;
  else if (list.n > 0) side = !list.c[0].entering;
  else if (kind == SolidKind::Quadric) side = leaf_inside(a, s, ray.at(std::isfinite(t_min) ? t_min : 0));  // unbounded
  out.start_inside = side;
  for (; i < list.n && list.c[i].t < t_max; ++i) {
    if (list.c[i].entering == side) continue;
    side = list.c[i].entering;
    if (!out.add(list.c[i].t, csg_part(leaf, list.c[i].part), side)) return;
  }
}

STRAHL_HOST_DEVICE inline bool csg_apply(CsgOp op, bool a, bool b) {
  return op == CsgOp::Intersection ? (a && b) : (a || b);
}

STRAHL_HOST_DEVICE inline void csg_invert(CsgList& l) {
  l.start_inside = !l.start_inside;
  for (int k = 0; k < l.n; ++k) {
    l.c[k].entering = !l.c[k].entering;
    l.c[k].part ^= kCsgFlip;
  }
}

// r = op(a, b) (Union, Intersection or Merge), by the rules at the top of this file.
STRAHL_HOST_DEVICE inline void csg_combine(CsgOp op, const CsgList& a, const CsgList& b, CsgList& r) {
  r.n = 0;
  r.valid_until = a.valid_until < b.valid_until ? a.valid_until : b.valid_until;
  bool sa = a.start_inside, sb = b.start_inside;
  bool side = csg_apply(op, sa, sb);
  r.start_inside = side;
  int ia = 0, ib = 0;
  for (;;) {
    const Real ta = ia < a.n ? a.c[ia].t : kInfinity, tb = ib < b.n ? b.c[ib].t : kInfinity;
    const Real t = ta < tb ? ta : tb;
    if (!(t < r.valid_until)) break;
    // The group of crossings at exactly t, from either operand.
    const int a0 = ia, b0 = ib;
    const bool sa0 = sa, sb0 = sb;
    while (ia < a.n && a.c[ia].t == t) sa = a.c[ia++].entering;
    while (ib < b.n && b.c[ib].t == t) sb = b.c[ib++].entering;
    const bool next = csg_apply(op, sa, sb);
    bool ok = true;
    if (op == CsgOp::Union) {
      for (int k = a0; k < ia && ok; ++k) ok = r.add(t, a.c[k].part, next);
      for (int k = b0; k < ib && ok; ++k) ok = r.add(t, b.c[k].part, next);
    } else if (next != side) {
      // One crossing stands for the change: the last of an operand whose side changed, A's first.
      const SolidCrossing& c = sa != sa0 ? a.c[ia - 1] : b.c[ib - 1];
      ok = r.add(t, c.part, next);
    } else if (op == CsgOp::Intersection && side) {
      // Inside both before and after: an operand's inner surfaces (its side unchanged) stay.
      if (sa == sa0)
        for (int k = a0; k < ia && ok; ++k) ok = r.add(t, a.c[k].part, next);
      if (sb == sb0)
        for (int k = b0; k < ib && ok; ++k) ok = r.add(t, b.c[k].part, next);
    }
    side = next;
    if (!ok) break;
  }
}

// A list whose crossings are at increasing t and alternate sides from its start (every leaf's,
// and most combined lists): combined with an operand that has no crossing and is the operation's
// identity (outside for a union or merge, inside for an intersection), csg_combine would copy it
// unchanged.
STRAHL_HOST_DEVICE inline bool csg_simple(const CsgList& l) {
  bool side = l.start_inside;
  for (int k = 0; k < l.n; ++k) {
    if (l.c[k].entering == side || (k > 0 && !(l.c[k].t > l.c[k - 1].t))) return false;
    side = l.c[k].entering;
  }
  return true;
}

// What csg_combine(op, a, b) gives without running it, where that is known from an operand with
// no crossing (most operands of a tree with many small ones miss the ray): First (a itself),
// Second (b), Empty (no crossing; the side the crossing-free operand has all along: an
// intersection with an operand outside everywhere, a merge with one inside everywhere), or None.
// Each is what csg_combine computes, bit for bit (tests/csg_test.cpp compares them).
enum class CsgShortcut : std::uint8_t { None, First, Second, Empty };
STRAHL_HOST_DEVICE inline CsgShortcut csg_shortcut(CsgOp op, const CsgList& a, const CsgList& b) {
  const bool intersection = op == CsgOp::Intersection;
  const bool b_plain = b.n == 0, a_plain = a.n == 0;
  if (!b_plain && !a_plain) return CsgShortcut::None;
  const CsgList& plain = b_plain ? b : a;
  // Outside everywhere for an intersection, inside everywhere for a merge: nothing can change.
  if ((intersection && !plain.start_inside) || (op == CsgOp::Merge && plain.start_inside)) return CsgShortcut::Empty;
  // The identity of the operation: the other list stays as it is, where it is simple and complete
  // at least as far as the plain one (else the combination would end where the plain one does).
  if (intersection != plain.start_inside) return CsgShortcut::None;  // a union with all inside
  const CsgList& other = b_plain ? a : b;
  if (plain.valid_until < other.valid_until || !csg_simple(other)) return CsgShortcut::None;
  return b_plain ? CsgShortcut::First : CsgShortcut::Second;
}

// The lists of the tree's program: kMaxCsgStack on the stack and one for the combining step's
// result. Left uninitialised (4.7 KB: clearing them cost more than the whole CSG query); every
// list's header is written before its crossings, and only crossings below n are read.
struct CsgStack {
  union {
    CsgList list[kMaxCsgStack + 1];
  };
  int slot[kMaxCsgStack + 1];  // stack position → list: a combined list takes its operand's slot, no copy
  STRAHL_HOST_DEVICE CsgStack() {}  // NOLINT(modernize-use-equals-default): = default would clear the lists
};

// Runs the tree's program over (t_min, t_max); returns the result (the bottom of the stack).
STRAHL_HOST_DEVICE inline const CsgList& csg_evaluate(const SolidArrays& a, const Csg& g, const Ray& ray, Real t_min,
                                                      Real t_max, CsgStack& st) {
  for (int k = 0; k <= kMaxCsgStack; ++k) st.slot[k] = k;
  const Vec3 inverse_direction(Real(1) / ray.direction.x, Real(1) / ray.direction.y, Real(1) / ray.direction.z);
  int sp = 0;
  for (std::uint32_t i = 0; i < g.instruction_count; ++i) {
    const CsgInstruction& in = a.csg_code[g.first_instruction + i];
    switch (in.op) {
      case CsgOp::Leaf:
        if (sp < kMaxCsgStack) {
          const CsgLeaf& leaf = a.csg_leaves[g.first_leaf + in.arg];
          CsgList& list = st.list[st.slot[sp++]];
          if (leaf.boxed && !hits(leaf.box, ray.origin, inverse_direction, t_min, t_max)) {
            list.n = 0;  // what csg_leaf_list finds there: no crossing, outside
            list.start_inside = false;
            list.valid_until = kInfinity;
          } else {
            csg_leaf_list(a, leaf.solid, in.arg, ray, t_min, t_max, list);
          }
        }
        break;
      case CsgOp::Inverse:
        if (sp >= 1) csg_invert(st.list[st.slot[sp - 1]]);
        break;
      case CsgOp::Skip:
        if (sp >= 1) {
          CsgList& first = st.list[st.slot[sp - 1]];
          // An intersection's (a difference's) list so far is nowhere on this ray: so is its result.
          if (in.run != CsgRun::Union && first.n == 0 && !first.start_inside) {
            i += in.arg;
            break;
          }
          // The steps' operands lie in a box that the ray's range misses (holes the ray does not
          // pass): each would be plain outside, so the steps' result is known (what csg_shortcut
          // says: an intersection with them is empty; a difference, a union or a merge with them
          // is the list so far itself where that is simple) without running them.
          if (in.box == kNoCsgBox || hits(a.csg_leaves[g.first_leaf + in.box].box, ray.origin, inverse_direction,
                                          t_min, t_max))
            break;
          if (in.run == CsgRun::Intersection) {
            first.n = 0;  // valid_until: the smaller of first's and ∞
            first.start_inside = false;
            i += in.arg;
          } else if (csg_simple(first)) {
            i += in.arg;
          }
        }
        break;
      default:
        if (sp >= 2) {
          CsgList& first = st.list[st.slot[sp - 2]];
          const CsgList& second = st.list[st.slot[sp - 1]];
          switch (csg_shortcut(in.op, first, second)) {
            case CsgShortcut::First: break;  // the result is the first list, where it is
            case CsgShortcut::Second: {
              const int second_slot = st.slot[sp - 1];
              st.slot[sp - 1] = st.slot[sp - 2];
              st.slot[sp - 2] = second_slot;
              break;
            }
            case CsgShortcut::Empty: {
              const Real until = first.valid_until < second.valid_until ? first.valid_until : second.valid_until;
              first.start_inside = second.n == 0 ? second.start_inside : first.start_inside;
              first.n = 0;
              first.valid_until = until;
              break;
            }
            case CsgShortcut::None: {
              csg_combine(in.op, first, second, st.list[st.slot[kMaxCsgStack]]);
              const int result = st.slot[kMaxCsgStack];
              st.slot[kMaxCsgStack] = st.slot[sp - 2];
              st.slot[sp - 2] = result;
              break;
            }
          }
          --sp;
        }
        break;
    }
  }
  if (sp == 0) st.list[st.slot[0]] = CsgList{};  // (the compiler never emits such a program)
  return st.list[st.slot[0]];
}

// Every crossing of the tree's surface in (t_min, t_max), front to back: calls visit(const
// SolidCrossing&), which returns true to stop.
template <class Visit>
STRAHL_HOST_DEVICE inline void for_each_csg_crossing(const SolidArrays& a, const Csg& g, const Ray& ray, Real t_min,
                                                     Real t_max, Visit&& visit) {
  CsgStack st;
  Real lo = t_min;
  for (int round = 0; round < kMaxCsgRounds; ++round) {
    const CsgList& r = csg_evaluate(a, g, ray, lo, t_max, st);
    for (int k = 0; k < r.n; ++k)
      if (r.c[k].t > lo && r.c[k].t < t_max && visit(r.c[k])) return;
    if (!(r.valid_until < t_max)) return;
    // Again from just before the first crossing the lists could not hold.
    const Real next = std::nextafter(r.valid_until, -kInfinity);
    if (!(next > lo)) return;  // no progress: more coincident crossings than a list holds
    lo = next;
  }
}

// Inside the tree: its program over the leaves' inside tests.
STRAHL_HOST_DEVICE inline bool csg_inside(const SolidArrays& a, const Csg& g, const Vec3& p) {
  bool st[kMaxCsgStack];
  int sp = 0;
  for (std::uint32_t i = 0; i < g.instruction_count; ++i) {
    const CsgInstruction& in = a.csg_code[g.first_instruction + i];
    switch (in.op) {
      case CsgOp::Leaf:
        if (sp < kMaxCsgStack) st[sp++] = leaf_inside(a, a.csg_leaves[g.first_leaf + in.arg].solid, p);
        break;
      case CsgOp::Inverse:
        if (sp >= 1) st[sp - 1] = !st[sp - 1];
        break;
      case CsgOp::Skip: break;  // (a shortcut for crossing lists; every operand is cheap here)
      default:
        if (sp >= 2) {
          st[sp - 2] = csg_apply(in.op, st[sp - 2], st[sp - 1]);
          --sp;
        }
        break;
    }
  }
  return sp > 0 && st[0];
}

// The outward normal of the tree at a crossing's part: its leaf's, flipped where the leaf is
// subtracted or inverted.
STRAHL_HOST_DEVICE inline Vec3 csg_normal_at(const SolidArrays& a, const Csg& g, std::uint32_t part, const Vec3& p) {
  const Solid& leaf = a.csg_leaves[g.first_leaf + (part >> 16)].solid;
  const Vec3 n = leaf_normal_at(a, leaf, int(part & 0x7fff), p);
  return (part & kCsgFlip) ? -n : n;
}

}  // namespace strahl::kernel
