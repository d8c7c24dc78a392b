// compile() for the solids of scene/solids.h: checks every value (an error names the object's
// file:line:column) and appends the kernel shape and its handle to the RenderScene.

#include <cmath>
#include <cstdio>
#include <cstring>

#include "strahl/render/render_scene.h"
#include "strahl/scene/move_solid.h"
#include "strahl/scene/place_solid.h"
#include "strahl/scene/solids.h"
#include "strahl/scene/validate.h"

namespace strahl {
namespace {

// Appends the handle, placed by the object's transform if it has one, and moved by its motion if
// it has one.
void push(RenderScene& out, const SceneObject& o, kernel::SolidKind kind, std::size_t index, std::uint32_t material) {
  out.solids.push_back({kind, static_cast<std::uint32_t>(index), material});
  if (o.placed()) place_last_solid(out, affine_of(o.placement), o.loc);
  if (o.motion.moving()) move_last_solid(out, o.motion, o.loc);
}

// Corners in any order → lo, hi; the box must have volume.
void box_corners(const Vec3& a, const Vec3& b, const FileLoc& loc, const std::string& what, Vec3& lo, Vec3& hi) {
  validate::finite(a, loc, what + " corner");
  validate::finite(b, loc, what + " corner");
  lo = min(a, b);
  hi = max(a, b);
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
    throw Error(loc, what + " is flat: its corners must differ in x, y and z");
}

}  // namespace

void Box::compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t) const {
  kernel::Box b;
  box_corners(corner_a, corner_b, loc, "box", b.lo, b.hi);
  out.boxes.push_back(b);
  push(out, *this, kernel::SolidKind::Box, out.boxes.size() - 1, material_index);
}

void Cone::compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t) const {
  const std::string what = is_cylinder ? "cylinder" : "cone";
  validate::finite(base, loc, what + " base");
  validate::finite(cap, loc, what + " cap");
  if (is_cylinder) {
    validate::positive(base_radius, loc, "cylinder radius");
  } else {
    validate::non_negative(base_radius, loc, "cone base radius");
    validate::non_negative(cap_radius, loc, "cone cap radius");
    if (!(base_radius > 0 || cap_radius > 0)) throw Error(loc, "cone radii are both 0 (one must be positive)");
  }
  const Real height = length(cap - base);
  if (!(height > 0) || !std::isfinite(height))
    throw Error(loc, "degenerate " + what + ": its base and cap are the same point");
  kernel::Cone c;
  c.base = base;
  c.axis = (cap - base) / height;
  c.height = height;
  c.base_radius = base_radius;
  c.cap_radius = cap_radius;
  c.open = open;
  out.cones.push_back(c);
  push(out, *this, kernel::SolidKind::Cone, out.cones.size() - 1, material_index);
}

void Disk::compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t) const {
  validate::finite(center, loc, "disk center");
  validate::non_zero(normal, loc, "disk normal");
  validate::positive(radius, loc, "disk radius");
  out.disks.push_back({center, normalize(normal), radius});
  push(out, *this, kernel::SolidKind::Disk, out.disks.size() - 1, material_index);
}

void Torus::compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t) const {
  validate::finite(center, loc, "torus center");
  validate::non_zero(axis, loc, "torus axis");
  validate::positive(major, loc, "torus major radius");
  validate::positive(minor, loc, "torus minor radius");
  if (!(minor < major))
    throw Error(loc, "torus minor radius (" + validate::str(minor) + ") must be smaller than its major radius (" +
                         validate::str(major) + ")");
  out.tori.push_back({center, normalize(axis), major, minor});
  push(out, *this, kernel::SolidKind::Torus, out.tori.size() - 1, material_index);
}

void Quadric::compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t) const {
  kernel::Quadric q;
  bool surface = false;
  for (std::size_t i = 0; i < 10; ++i) {
    validate::finite(coefficients[i], loc, "quadric coefficient");
    surface = surface || (i < 9 && coefficients[i] != 0);
  }
  // One copy, not a loop of stores (see tests/solid_test.cpp: a GCC 12.2 AVX-512 miscompile).
  std::memcpy(q.coef, coefficients.data(), sizeof q.coef);
  if (!surface) throw Error(loc, "quadric describes no surface: its coefficients A to I are all 0");
  if (clip) {
    q.clipped = true;
    box_corners(clip->a, clip->b, loc, "quadric clip box", q.lo, q.hi);
  }
  out.quadrics.push_back(q);
  push(out, *this, kernel::SolidKind::Quadric, out.quadrics.size() - 1, material_index);
}

void ImplicitSurface::compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t) const {
  kernel::Implicit s;
  try {
    s.f = compile_expression(expression, parameters);
  } catch (const ExpressionError& e) {
    throw Error(loc, "implicit expression: " + std::string(e.what()));
  }
  if (!uses_coordinates(s.f)) throw Error(loc, "implicit expression does not use x, y or z: it describes no surface");
  s.bound = bound;
  Real diameter = 0;
  if (bound == kernel::ImplicitBound::Box) {
    box_corners(box_a, box_b, loc, "implicit contained_by box", s.lo, s.hi);
    diameter = length(s.hi - s.lo);
  } else {
    validate::finite(center, loc, "implicit contained_by sphere center");
    validate::positive(radius, loc, "implicit contained_by sphere radius");
    s.center = center;
    s.radius = radius;
    diameter = 2 * radius;
  }
  s.method = method;
  validate::positive(max_gradient, loc, "implicit max_gradient");
  validate::positive(accuracy, loc, "implicit accuracy");
  s.max_gradient = max_gradient;
  s.accuracy = accuracy;
  // geometry/implicit.h: the bisection's stack spans 2^40 accuracies, the evaluation budget 2^16
  // samples per ray; keep well inside both.
  if (diameter / accuracy > Real(1 << 20))
    throw Error(loc, "implicit accuracy " + validate::str(accuracy) + " is too fine for a bound " +
                         validate::str(diameter) + " across (at most 2^20 accuracies across; use at least " +
                         validate::str(diameter / Real(1 << 20)) + ")");
  s.step = step > 0 ? step : accuracy * 10;
  if (method == kernel::RootMethod::March && diameter / s.step > Real(1 << 14))
    throw Error(loc, "implicit step " + validate::str(s.step) + " is too small for a bound " + validate::str(diameter) +
                         " across (at most 16384 steps across; use at least " +
                         validate::str(diameter / Real(1 << 14)) + ")");
  if (!(step >= 0)) throw Error(loc, "implicit step must be positive (got " + validate::str(step) + ")");
  // Central differences a millionth of the bound across: far above f's rounding, far below any
  // feature the accuracy resolves.
  s.normal_step = diameter * Real(1e-6);
  s.material = material_index;
  out.implicits.push_back(s);
  out.implicit_tallies.push_back({});
  out.implicit_locs.push_back(loc);
  push(out, *this, kernel::SolidKind::Implicit, out.implicits.size() - 1, material_index);
}

namespace {
std::string g(Real v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}
}  // namespace

std::vector<std::string> implicit_warnings(const RenderScene& scene) {
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < scene.implicit_tallies.size(); ++i) {
    const kernel::ImplicitTally& t = scene.implicit_tallies[i];
    const Real met = kernel::max_gradient_of(t), declared = scene.implicits[i].max_gradient;
    const std::string where = scene.implicit_locs[i].str();
    const std::string name = where.empty() ? "implicit surface " + std::to_string(i + 1) : where;
    // Marching takes fixed steps: its max_gradient plays no part.
    if (scene.implicits[i].method != kernel::RootMethod::March && met > declared)
      lines.push_back(name + ": the implicit surface's gradient reached " + g(met, 4) + ", above its max_gradient " +
                      g(declared, 4) + ": surfaces may have holes (use max_gradient: " + g(met * 1.05, 3) + ")");
    if (t.exhausted > 0)
      lines.push_back(name + ": " + std::to_string(t.exhausted) + " rays gave up on the implicit surface after " +
                      std::to_string(kernel::kMaxImplicitEvaluations) + " evaluations of f (raise accuracy or step)");
  }
  return lines;
}

}  // namespace strahl
