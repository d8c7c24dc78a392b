#pragma once
// The map that carries a moving solid or instance (motion blur; geometry/moving_solid.h,
// geometry/moving_instance.h) over the shutter fraction u ∈ [0, 1]:
//
//   A(u)·x = Post(Rot(axis, u·angle)·(L(u)·x − c(u)) + t(u)),
//   L(u) = (1 − u)·L₀ + u·L₁,  c(u) = (1 − u)·c₀ + u·c₁,  t(u) = (1 − u)·t₀ + u·t₁.
//
// Without a turn (angle 0: a velocity, keyframes that scale and translate) c is 0 and A(u) is the
// blend of the keys: every point moves on a segment. Keyframes that turn are split
// (scene/move_solid.h) into the turn between them, taken uniformly over the shutter about a fixed
// axis (its angle below a half turn), and the rest, blended: L₀ is the first key's linear part,
// L₁ the second's with the turn taken out — every point then moves on an arc, and the object keeps
// its shape. A spin is such a turn of any angle about the line through a centre p: cᵢ = Lᵢ·p is
// where the keys' linear parts take that centre, and tᵢ where the keys take it, so the points on
// the line stay on it (elsewhere c is 0: the turn is about the keys' origin). Post is a fixed map
// after the motion (a mesh's own transform: its keyframes act before it), or none. A ray at time u
// is brought to the unmoved object by A(u)⁻¹ (a placement, geometry/placement.h), where its t is
// the same; normals come back by A(u)⁻ᵀ. scene/move_solid.h checks that A(u) is invertible at
// every u.

#include <cmath>
#include <cstdint>
#include <initializer_list>

#include "strahl/geometry/moving.h"
#include "strahl/geometry/placement.h"
#include "strahl/math/bounds.h"

namespace strahl::kernel {

struct MovingMap {
  Vec3 linear0[3], linear1[3];   // A's linear part at shutter open and at close, by rows
  Vec3 translate0, translate1;   // A's translation at shutter open and at close
  // Where the linear part is the same at both keys (a velocity, keyframes that only translate),
  // its inverse, the same at every u: the one at_time() would compute, bit for bit.
  Vec3 fixed_inverse[3];
  std::uint32_t fixed = 0;
  std::uint32_t post = 0;        // 1: A(u) is followed by the fixed map below
  std::uint32_t pivot = 0;       // 1: the turn is about a spin's centre (c₀, c₁ below), 0: c is 0
  Vec3 pivot0{0}, pivot1{0};     // c₀, c₁
  Vec3 axis{0, 0, 1};            // the turn's axis (unit length), and its angle (radians; 0: none)
  Real angle = 0;
  Vec3 post_row[3];              // Post's linear part, by rows, and its inverse
  Vec3 post_inverse[3];
  Vec3 post_translate{0};
};

// The Frobenius norm of the 3×3 map with these rows: it bounds how far the map stretches.
STRAHL_HOST_DEVICE inline Real frobenius(const Vec3* rows) {
  return std::sqrt(dot(rows[0], rows[0]) + dot(rows[1], rows[1]) + dot(rows[2], rows[2]));
}

// The turn by `angle` about the unit `axis` (Rodrigues), by rows.
STRAHL_HOST_DEVICE inline void turn_rows(const Vec3& a, Real angle, Vec3* r) {
  const Real c = std::cos(angle), s = std::sin(angle), k = 1 - c;
  r[0] = Vec3(c + k * a.x * a.x, k * a.x * a.y - s * a.z, k * a.x * a.z + s * a.y);
  r[1] = Vec3(k * a.x * a.y + s * a.z, c + k * a.y * a.y, k * a.y * a.z - s * a.x);
  r[2] = Vec3(k * a.x * a.z - s * a.y, k * a.y * a.z + s * a.x, c + k * a.z * a.z);
}

// The inverse of the linear part with rows r0, r1, r2, by cofactors.
STRAHL_HOST_DEVICE inline void inverse_rows(const Vec3& r0, const Vec3& r1, const Vec3& r2, Vec3* out) {
  const Vec3 c0 = cross(r1, r2), c1 = cross(r2, r0), c2 = cross(r0, r1);
  const Real inv_det = 1 / dot(r0, c0);
  out[0] = Vec3(c0.x, c1.x, c2.x) * inv_det;
  out[1] = Vec3(c0.y, c1.y, c2.y) * inv_det;
  out[2] = Vec3(c0.z, c1.z, c2.z) * inv_det;
}

// world → the unmoved object's space at time u: A(u)⁻¹. A velocity's linear part is the identity
// at both keys, and so exactly the identity here: such an object is met where the ray itself,
// displaced, meets the unmoved one.
STRAHL_HOST_DEVICE inline Placement at_time(const MovingMap& m, Real u) {
  Placement x;
  x.translate = lerp(m.translate0, m.translate1, u);
  if (m.fixed != 0) {
    x.row[0] = m.fixed_inverse[0];
    x.row[1] = m.fixed_inverse[1];
    x.row[2] = m.fixed_inverse[2];
  } else {
    const Vec3 r0 = lerp(m.linear0[0], m.linear1[0], u), r1 = lerp(m.linear0[1], m.linear1[1], u),
               r2 = lerp(m.linear0[2], m.linear1[2], u);
    inverse_rows(r0, r1, r2, x.row);
  }
  if (m.angle != 0) {  // (Rot·L)⁻¹ = L⁻¹·Rotᵀ: row i of it is (L⁻¹ row i)·(Rot's rows)
    Vec3 turn[3];
    turn_rows(m.axis, m.angle * u, turn);
    for (Vec3& row : x.row) row = Vec3(dot(row, turn[0]), dot(row, turn[1]), dot(row, turn[2]));
    if (m.pivot != 0) {  // A(u)·x = Rot·L(u)·x + (t(u) − Rot·c(u))
      const Vec3 c = lerp(m.pivot0, m.pivot1, u);
      x.translate = x.translate - Vec3(dot(turn[0], c), dot(turn[1], c), dot(turn[2], c));
    }
  }
  if (m.post != 0) {  // A(u)⁻¹(p) = B⁻¹·(P⁻¹·(p − p_t) − t(u)) = B⁻¹·P⁻¹·(p − (p_t + P·t(u)))
    x.translate = m.post_translate + Vec3(dot(m.post_row[0], x.translate), dot(m.post_row[1], x.translate),
                                          dot(m.post_row[2], x.translate));
    for (Vec3& row : x.row)
      row = m.post_inverse[0] * row.x + m.post_inverse[1] * row.y + m.post_inverse[2] * row.z;
  }
  return x;
}

// Where A(u) takes p (host: bounds and tests).
inline Vec3 moved_point(const MovingMap& m, const Vec3& p, Real u) {
  const Vec3 r0 = lerp(m.linear0[0], m.linear1[0], u), r1 = lerp(m.linear0[1], m.linear1[1], u),
             r2 = lerp(m.linear0[2], m.linear1[2], u);
  Vec3 q(dot(r0, p), dot(r1, p), dot(r2, p));
  if (m.pivot != 0) q = q - lerp(m.pivot0, m.pivot1, u);
  if (m.angle != 0) {
    Vec3 turn[3];
    turn_rows(m.axis, m.angle * u, turn);
    q = Vec3(dot(turn[0], q), dot(turn[1], q), dot(turn[2], q));
  }
  q = q + lerp(m.translate0, m.translate1, u);
  if (m.post != 0) q = Vec3(dot(m.post_row[0], q), dot(m.post_row[1], q), dot(m.post_row[2], q)) + m.post_translate;
  return q;
}

// The box holding everything within the box [lo, hi] at every time of [u0, u1]. Without a turn
// each point moves on a segment between where A(u0) and A(u1) put it, and lies in the hull of
// the moved corners (up to rounding, as a placed solid's box: geometry/solid_leaf.h). With one,
// a point x is at t(u) + Rot(u)·y(u), y(u) = L(u)·x − c(u); with s the fraction of the segment,
// y(u) = (1 − s)·y₀ + s·y₁ (y at u0 and u1) and t(u) likewise, so the point is (1 − s)·(t(u0) +
// Rot(u)·y₀) + s·(t(u1) + Rot(u)·y₁), in the hull of the arcs tᵢ + Rot(φ)·yᵢ over the segment's
// angles φ. The arcs are cut into pieces of at most an eighth of a turn (a whole turn at most:
// beyond it they close), and a piece of turn δ lies within |y|·(1 − cos(δ/2)) of its chord. So
// the point lies in the hull of the points tᵢ + Rot(φₖ)·yᵢ at the pieces' ends, widened by that;
// Post carries the hull to the hull of its image and stretches the widening by at most its
// Frobenius norm. Widened by a little more than rounding.
inline Bounds swept_bounds(const MovingMap& m, const Vec3& lo, const Vec3& hi, Real u0, Real u1) {
  Bounds box;
  if (m.angle == 0 && m.post == 0) {
    for (const Real u : {u0, u1})
      for (int c = 0; c < 8; ++c)
        box.extend(moved_point(m, Vec3((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z), u));
    return box;
  }
  constexpr int kMostPieces = 8;
  const Real sweep = m.angle * (u1 - u0);
  const bool whole = std::fabs(sweep) >= 2 * kPi;
  const Real span = whole ? std::copysign(2 * kPi, sweep) : sweep;
  const int pieces = whole ? kMostPieces : std::fabs(sweep) > kPi / 4 ? int(std::ceil(std::fabs(sweep) / (kPi / 4))) : 1;
  Vec3 turn[kMostPieces + 1][3];
  for (int k = 0; k <= pieces; ++k)
    turn_rows(m.axis, k == pieces && !whole ? m.angle * u1 : m.angle * u0 + span * k / pieces, turn[k]);
  const Real half = std::fabs(span / pieces) / 4, sag_per_length = 2 * std::sin(half) * std::sin(half);
  Real reach = 0;
  const Real us[2] = {u0, u1};
  for (int c = 0; c < 8; ++c) {
    const Vec3 x((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    for (const Real u : us) {
      const Vec3 r0 = lerp(m.linear0[0], m.linear1[0], u), r1 = lerp(m.linear0[1], m.linear1[1], u),
                 r2 = lerp(m.linear0[2], m.linear1[2], u);
      Vec3 y(dot(r0, x), dot(r1, x), dot(r2, x));
      if (m.pivot != 0) y = y - lerp(m.pivot0, m.pivot1, u);
      const Vec3 t = lerp(m.translate0, m.translate1, u);
      reach = std::fmax(reach, length(y));
      for (int k = 0; k <= pieces; ++k) {
        const Vec3* r = turn[k];
        Vec3 q = Vec3(dot(r[0], y), dot(r[1], y), dot(r[2], y)) + t;
        if (m.post != 0) q = Vec3(dot(m.post_row[0], q), dot(m.post_row[1], q), dot(m.post_row[2], q)) + m.post_translate;
        box.extend(q);
      }
    }
  }
  const Real stretch = m.post != 0 ? frobenius(m.post_row) : 1;
  const Real pad = reach * stretch * sag_per_length * Real(1.000001) +
                   Real(1e-9) * std::fmax(std::fmax(max_abs_component(box.lo), max_abs_component(box.hi)), reach * stretch);
  box.lo = box.lo - Vec3(pad);
  box.hi = box.hi + Vec3(pad);
  return box;
}

}  // namespace strahl::kernel
