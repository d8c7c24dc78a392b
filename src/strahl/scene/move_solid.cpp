// validate_motion, moving_map and move_last_solid (scene/move_solid.h).

#include "strahl/scene/move_solid.h"

#include <cmath>
#include <initializer_list>

#include "strahl/geometry/moving_solid.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/validate.h"

namespace strahl {

void validate_motion(const Motion& m, const FileLoc& loc) {
  validate::finite(m.spin().axis, loc, "motion spin axis");
  validate::finite(m.spin().angle, loc, "motion spin angle");
  validate::finite(m.spin().center, loc, "motion spin center");
  if (m.spins() && m.spin().axis == Vec3(0)) throw Error(loc, "motion spin axis must not be zero");
  if (m.kind == Motion::Kind::Velocity) validate::finite(m.velocity(), loc, "motion velocity");
  if (m.kind != Motion::Kind::Keyframes) return;
  for (const Transform* t : {&m.from(), &m.to()}) {
    validate::finite(t->scale, loc, "motion scale");
    validate::finite(t->rotate_degrees, loc, "motion rotate");
    validate::finite(t->translate, loc, "motion translate");
    if (t->linear().determinant() == 0) throw Error(loc, "motion scale must not be zero");
  }
}

namespace {

// The motion's map at shutter open (key 0) and close (key 1), in world space.
Affine motion_key(const Motion& m, Real shutter_open, Real shutter_close, int key) {
  switch (m.kind) {
    case Motion::Kind::Velocity: return {Mat3{}, m.velocity() * (key == 0 ? shutter_open : shutter_close)};
    case Motion::Kind::Keyframes: return affine_of(key == 0 ? m.from() : m.to());
    case Motion::Kind::None: break;
  }
  return {};
}

Real det(const Vec3& a, const Vec3& b, const Vec3& c) { return dot(a, cross(b, c)); }

// Is A(u)'s linear part, (1 − u)·L0 + u·L1 by rows, invertible at every u ∈ [0, 1]? Its
// determinant p(u) is a cubic in u; between the roots of p′ it is monotone, so it has no root in
// [0, 1] when it has one sign at 0, at 1 and at the roots of p′ between them — and is not nearly
// 0 at any of them: neither flat (|p| against the product of the rows' lengths: a billionth) nor
// shrunk to a point (|p|^⅓ against the keys' longest row: a millionth; a half turn's chords
// meet at the axis, where rounding leaves rows of 1e-16).
bool invertible_throughout(const kernel::MovingMap& m) {
  Real reach = 0;
  for (int i = 0; i < 3; ++i) reach = std::fmax(reach, std::fmax(length(m.linear0[i]), length(m.linear1[i])));
  const Vec3* l = m.linear0;
  Vec3 d[3];
  for (int i = 0; i < 3; ++i) d[i] = m.linear1[i] - l[i];
  const Real a1 = det(d[0], l[1], l[2]) + det(l[0], d[1], l[2]) + det(l[0], l[1], d[2]);
  const Real a2 = det(l[0], d[1], d[2]) + det(d[0], l[1], d[2]) + det(d[0], d[1], l[2]);
  const Real a3 = det(d[0], d[1], d[2]);
  // p′(u) = a1 + 2·a2·u + 3·a3·u².
  Real at[4] = {0, 1, 0, 0};
  int n = 2;
  if (a3 != 0) {
    const Real disc = a2 * a2 - 3 * a1 * a3;
    if (disc >= 0) {
      const Real s = std::sqrt(disc);
      at[n++] = (-a2 - s) / (3 * a3);
      at[n++] = (-a2 + s) / (3 * a3);
    }
  } else if (a2 != 0) {
    at[n++] = -a1 / (2 * a2);
  }
  Real sign = 0;
  for (int i = 0; i < n; ++i) {
    const Real u = at[i];
    if (!(u >= 0 && u <= 1)) continue;
    const Vec3 r0 = kernel::lerp(m.linear0[0], m.linear1[0], u), r1 = kernel::lerp(m.linear0[1], m.linear1[1], u),
               r2 = kernel::lerp(m.linear0[2], m.linear1[2], u);
    const Real p = det(r0, r1, r2), flat = p / (length(r0) * length(r1) * length(r2));
    if (!(std::fabs(flat) > Real(1e-9)) || !(std::cbrt(std::fabs(p)) > Real(1e-6) * reach)) return false;
    if (sign == 0) sign = p;
    if ((p > 0) != (sign > 0)) return false;
  }
  return true;
}

Real frobenius(const Mat3& a) { return kernel::frobenius(a.row); }

// The orthogonal factor Q of the polar decomposition L = Q·S (S symmetric, positive definite;
// det Q has det L's sign): Higham's Newton iteration Q ← (γ·Q + Q⁻ᵀ/γ)/2, scaled by
// γ = (‖Q⁻¹‖/‖Q‖)^½ (Frobenius), which converges in a handful of steps even for long, thin maps.
Mat3 orthogonal_factor(const Mat3& l) {
  Mat3 q = l;
  for (int step = 0; step < 100; ++step) {
    const Mat3 inv_t = q.inverse().transposed();
    const Real g = std::sqrt(frobenius(inv_t) / frobenius(q));
    Mat3 next;
    Real change = 0;
    for (int i = 0; i < 3; ++i) {
      next.row[i] = (q.row[i] * g + inv_t.row[i] / g) * Real(0.5);
      change = std::fmax(change, max_abs_component(next.row[i] - q.row[i]));
    }
    q = next;
    if (!(change > Real(1e-15))) break;
  }
  return q;
}

// The turn from the orthogonal q0 to q1 (q1·q0ᵀ, whose determinant is 1): its axis (unit
// length; right-handed) and angle in [0, π]. sin(angle)·axis is the skew part's vector and
// cos(angle) = (trace − 1)/2; past a quarter turn the axis comes from the symmetric part,
// (d + dᵀ)/2 − cos·I = (1 − cos)·axis·axisᵀ, where the skew part has become small.
void turn_between(const Mat3& q0, const Mat3& q1, Vec3& axis, Real& angle) {
  const Mat3 d = q1 * q0.transposed();
  const Vec3 v((d.row[2].y - d.row[1].z) / 2, (d.row[0].z - d.row[2].x) / 2, (d.row[1].x - d.row[0].y) / 2);
  const Real c = (d.row[0].x + d.row[1].y + d.row[2].z - 1) / 2, s = length(v);
  angle = std::atan2(s, c);
  axis = s > 0 ? v / s : Vec3(0, 0, 1);
  if (angle > kPi / 2) {
    const Mat3 dt = d.transposed();
    Mat3 sym;
    for (int i = 0; i < 3; ++i) sym.row[i] = (d.row[i] + dt.row[i]) * Real(0.5);
    sym.row[0].x -= c;
    sym.row[1].y -= c;
    sym.row[2].z -= c;
    int k = 0;
    if (sym.row[1].y > sym.row[k][k]) k = 1;
    if (sym.row[2].z > sym.row[k][k]) k = 2;
    axis = normalize(sym.row[k]);
    if (dot(axis, v) < 0) axis = -axis;
  }
}

// The turn between keyframes (their linear parts' orthogonal factors differ; both mirror or
// neither — else there is none, and a blend of them flattens, which moving_map refuses): its axis
// and angle, and whether there is one (an angle above 1e-9). Keyframes a half turn apart are an
// error at `loc`: which way they turn is open.
bool keys_turn(const Motion& motion, const Affine* key_map, Vec3& axis, Real& angle, const FileLoc& loc, const char* what) {
  const Real det0 = key_map[0].m.determinant(), det1 = key_map[1].m.determinant();
  if (motion.kind != Motion::Kind::Keyframes || (det0 > 0) != (det1 > 0)) return false;
  turn_between(orthogonal_factor(key_map[0].m), orthogonal_factor(key_map[1].m), axis, angle);
  if (kPi - angle < Real(1e-6))
    throw Error(loc, std::string("the keyframes of the ") + what +
                         " are a half turn apart, so which way it turns is open: turn it by less within the shutter, "
                         "or give the turn as a spin");
  if (angle > Real(1e-9)) return true;
  axis = Vec3(0, 0, 1);
  angle = 0;
  return false;
}

// The motion's turn: its spin's, or the keyframes' (above) — not both (an error at `loc`).
bool turn_of(const Motion& motion, const Affine* key_map, Vec3& axis, Real& angle, const FileLoc& loc, const char* what) {
  const bool keys = keys_turn(motion, key_map, axis, angle, loc, what);
  if (!motion.spins()) return keys;
  if (keys)
    throw Error(loc, std::string("the keyframes of the ") + what +
                         " turn, and so does its spin: give the keyframes the same rotation and the whole turn to the spin");
  axis = normalize(motion.spin().axis);
  angle = motion.spin().angle * kPi / 180;
  return true;
}

}  // namespace

void set_post(kernel::MovingMap& map, const Affine& post) {
  const Mat3 identity;
  if (post.m.row[0] == identity.row[0] && post.m.row[1] == identity.row[1] && post.m.row[2] == identity.row[2] &&
      post.t == Vec3(0))
    return;
  map.post = 1;
  const Mat3 inv = post.m.inverse();
  for (int i = 0; i < 3; ++i) {
    map.post_row[i] = post.m.row[i];
    map.post_inverse[i] = inv.row[i];
  }
  map.post_translate = post.t;
}

Affine post_map(const kernel::MovingMap& map) {
  Affine a{Mat3{}, map.post_translate};
  for (int i = 0; i < 3; ++i) a.m.row[i] = map.post_row[i];
  return a;
}

Affine mesh_motion_post(const Transform& transform, const FileLoc& loc) {
  validate::finite(transform.scale, loc, "mesh scale");
  validate::finite(transform.rotate_degrees, loc, "mesh rotate");
  validate::finite(transform.translate, loc, "mesh translate");
  const Affine post = affine_of(transform);
  if (!(std::fabs(post.m.determinant()) > 0)) throw Error(loc, "mesh scale must not be zero");
  return post;
}

kernel::MovingMap moving_map(const Motion& motion, const Camera& camera, const FileLoc& loc, const char* what,
                             const Affine* post) {
  validate_motion(motion, loc);
  kernel::MovingMap m;
  Affine key_map[2];
  for (int key = 0; key < 2; ++key) {
    key_map[key] = motion_key(motion, camera.shutter_open, camera.shutter_close, key);
    for (int i = 0; i < 3; ++i) (key == 0 ? m.linear0 : m.linear1)[i] = key_map[key].m.row[i];
    (key == 0 ? m.translate0 : m.translate1) = key_map[key].t;
  }
  // A turn between the keys: taken out of the second key, and taken uniformly over the shutter by
  // at_time() (geometry/moving_map.h).
  if (turn_of(motion, key_map, m.axis, m.angle, loc, what) && motion.spins()) {
    // About the spin's centre p: cᵢ = Lᵢ·p, and tᵢ is where the key takes p.
    m.pivot = 1;
    const Vec3 p = motion.spin().center;
    for (int key = 0; key < 2; ++key) {
      const Mat3& l = key_map[key].m;
      const Vec3 c(dot(l.row[0], p), dot(l.row[1], p), dot(l.row[2], p));
      (key == 0 ? m.pivot0 : m.pivot1) = c;
      (key == 0 ? m.translate0 : m.translate1) = key_map[key].t + c;
    }
  } else if (m.angle != 0) {
    Vec3 turn[3];
    kernel::turn_rows(m.axis, m.angle, turn);
    // L₁ = Rot(angle)ᵀ·(the second key's linear part), by rows: row i is Σₖ Rot[k][i]·key row k.
    const Mat3& l1 = key_map[1].m;
    for (int i = 0; i < 3; ++i)
      m.linear1[i] = Vec3(turn[0][i] * l1.row[0].x + turn[1][i] * l1.row[1].x + turn[2][i] * l1.row[2].x,
                          turn[0][i] * l1.row[0].y + turn[1][i] * l1.row[1].y + turn[2][i] * l1.row[2].y,
                          turn[0][i] * l1.row[0].z + turn[1][i] * l1.row[1].z + turn[2][i] * l1.row[2].z);
    // A pure turn (the keys' linear parts the same but for it) leaves L₁ = L₀ up to rounding:
    // made exact, so that the inverse is computed once (below) and at_time() only turns it.
    Real off = 0, size = 0;
    for (int i = 0; i < 3; ++i) {
      off = std::fmax(off, max_abs_component(m.linear1[i] - m.linear0[i]));
      size = std::fmax(size, max_abs_component(m.linear0[i]));
    }
    if (off <= Real(1e-13) * size)
      for (int i = 0; i < 3; ++i) m.linear1[i] = m.linear0[i];
  }
  if (post != nullptr) set_post(m, *post);
  // lerp(L, L, u) = L + (L − L)·u = L + 0 is the same at every u ∈ [0, 1] (L itself but for a −0,
  // which becomes +0): at_time()'s inverse of it too, computed here once.
  if (m.linear0[0] == m.linear1[0] && m.linear0[1] == m.linear1[1] && m.linear0[2] == m.linear1[2]) {
    m.fixed = 1;
    kernel::inverse_rows(kernel::lerp(m.linear0[0], m.linear1[0], 0), kernel::lerp(m.linear0[1], m.linear1[1], 0),
                         kernel::lerp(m.linear0[2], m.linear1[2], 0), m.fixed_inverse);
  }
  if (!invertible_throughout(m))
    throw Error(loc, std::string("the motion flattens the ") + what +
                         " during the shutter: a scale that changes sign between the keyframes passes through a "
                         "flat map (as does one near 0)");
  return m;
}

bool motion_turns(const Motion& motion, const Camera& camera, const FileLoc& loc, const char* what) {
  if (motion.kind != Motion::Kind::Keyframes && !motion.spins()) return false;
  validate_motion(motion, loc);
  const Affine key_map[2] = {motion_key(motion, camera.shutter_open, camera.shutter_close, 0),
                             motion_key(motion, camera.shutter_open, camera.shutter_close, 1)};
  Vec3 axis;
  Real angle = 0;
  return turn_of(motion, key_map, axis, angle, loc, what);
}

void move_last_solid(RenderScene& out, const Motion& motion, const FileLoc& loc) {
  kernel::MovingSolid m;
  m.solid = out.solids.back();
  const Bounds b = kernel::bounds(out.shapes(), m.solid);
  if (!(std::isfinite(b.lo.x) && std::isfinite(b.lo.y) && std::isfinite(b.lo.z) && std::isfinite(b.hi.x) &&
        std::isfinite(b.hi.y) && std::isfinite(b.hi.z)))
    throw Error(loc, "a solid without bounds cannot move (an unclipped quadric, or a CSG tree around an inverse: "
                     "clip it, or intersect it with a box)");
  m.lo = b.lo;
  m.hi = b.hi;
  m.map = moving_map(motion, out.camera, loc, "solid");
  const Bounds swept = kernel::swept_bounds(m);
  validate::coordinates(swept.lo, loc, "moving solid's bounds");
  validate::coordinates(swept.hi, loc, "moving solid's bounds");
  out.solids.pop_back();
  out.moving_solids.push_back(m);
}

}  // namespace strahl
