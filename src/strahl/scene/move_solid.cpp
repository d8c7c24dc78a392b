// validate_motion, moving_map and move_last_solid (scene/move_solid.h).

#include "strahl/scene/move_solid.h"

#include <cmath>
#include <initializer_list>

#include "strahl/geometry/moving_solid.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/validate.h"

namespace strahl {

void validate_motion(const Motion& m, const FileLoc& loc) {
  if (m.kind == Motion::Kind::Velocity) validate::finite(m.velocity, loc, "motion velocity");
  if (m.kind != Motion::Kind::Keyframes) return;
  for (const Transform* t : {&m.from, &m.to}) {
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
    case Motion::Kind::Velocity: return {Mat3{}, m.velocity * (key == 0 ? shutter_open : shutter_close)};
    case Motion::Kind::Keyframes: return affine_of(key == 0 ? m.from : m.to);
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

}  // namespace

kernel::MovingMap moving_map(const Motion& motion, const Camera& camera, const FileLoc& loc, const char* what) {
  validate_motion(motion, loc);
  kernel::MovingMap m;
  for (int key = 0; key < 2; ++key) {
    const Affine a = motion_key(motion, camera.shutter_open, camera.shutter_close, key);
    for (int i = 0; i < 3; ++i) (key == 0 ? m.linear0 : m.linear1)[i] = a.m.row[i];
    (key == 0 ? m.translate0 : m.translate1) = a.t;
  }
  // lerp(L, L, u) = L + (L − L)·u = L + 0 is the same at every u ∈ [0, 1] (L itself but for a −0,
  // which becomes +0): at_time()'s inverse of it too, computed here once.
  if (m.linear0[0] == m.linear1[0] && m.linear0[1] == m.linear1[1] && m.linear0[2] == m.linear1[2]) {
    m.fixed = 1;
    kernel::inverse_rows(kernel::lerp(m.linear0[0], m.linear1[0], 0), kernel::lerp(m.linear0[1], m.linear1[1], 0),
                         kernel::lerp(m.linear0[2], m.linear1[2], 0), m.fixed_inverse);
  }
  if (!invertible_throughout(m))
    throw Error(loc, std::string("the motion flattens the ") + what +
                         " during the shutter: its points move on straight lines between the keyframes, so a half "
                         "turn (or a scale that changes sign) passes through a flat map; turn it by less within the "
                         "shutter");
  return m;
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
