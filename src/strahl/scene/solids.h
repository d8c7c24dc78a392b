#pragma once
// The solids of the scene API and scene files (docs/scene-format.md): box, cylinder, cone, disk,
// torus, quadric and implicit surfaces. compile() turns each into a kernel shape of
// geometry/solid.h; the values are checked there (throwing strahl::Error at the object's `loc`).

#include <array>
#include <optional>
#include <string>

#include "strahl/geometry/implicit.h"
#include "strahl/scene/expression_compiler.h"
#include "strahl/scene/scene.h"

namespace strahl {

// An axis-aligned box given by two opposite corners (in any order).
class Box : public SceneObject {
 public:
  Box(const Vec3& a, const Vec3& b, const Material& m) : SceneObject(m), corner_a(a), corner_b(b) {}
  void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const override;

  Vec3 corner_a, corner_b;
};

// A truncated cone from `base` (radius base_radius) to `cap` (radius cap_radius); a cylinder has
// equal radii (Cone::cylinder). One radius may be 0 (a pointed cone). Open: no end caps.
class Cone : public SceneObject {
 public:
  Cone(const Vec3& base_, Real base_radius_, const Vec3& cap_, Real cap_radius_, const Material& m, bool open_ = false)
      : SceneObject(m), base(base_), cap(cap_), base_radius(base_radius_), cap_radius(cap_radius_), open(open_) {}
  static Cone cylinder(const Vec3& base, const Vec3& cap, Real radius, const Material& m, bool open = false) {
    Cone c(base, radius, cap, radius, m, open);
    c.is_cylinder = true;
    return c;
  }
  void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const override;

  Vec3 base, cap;
  Real base_radius, cap_radius;
  bool open = false;
  bool is_cylinder = false;  // for messages
};

class Disk : public SceneObject {
 public:
  Disk(const Vec3& center_, const Vec3& normal_, Real radius_, const Material& m)
      : SceneObject(m), center(center_), normal(normal_), radius(radius_) {}
  void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const override;

  Vec3 center, normal;
  Real radius;
};

// A ring torus around `axis` (need not be unit) through `center`: 0 < minor < major.
class Torus : public SceneObject {
 public:
  Torus(const Vec3& center_, Real major_, Real minor_, const Material& m, const Vec3& axis_ = Vec3(0, 1, 0))
      : SceneObject(m), center(center_), axis(axis_), major(major_), minor(minor_) {}
  void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const override;

  Vec3 center, axis;
  Real major, minor;
};

// Ax² + By² + Cz² + Dxy + Exz + Fyz + Gx + Hy + Iz + J = 0 (inside: < 0), optionally clipped by a
// box (only the surface within it is kept). Unclipped, it stays outside the acceleration
// structure, as planes do.
struct ClipBox {
  Vec3 a, b;
};
class Quadric : public SceneObject {
 public:
  Quadric(const std::array<Real, 10>& coefficients_, const Material& m, std::optional<ClipBox> clip_ = {})
      : SceneObject(m), coefficients(coefficients_), clip(clip_) {}
  void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const override;

  std::array<Real, 10> coefficients;
  std::optional<ClipBox> clip;
};

// f(x, y, z) < 0 within a bound (geometry/implicit.h), f written in the expression language of
// scene/expression_compiler.h.
class ImplicitSurface : public SceneObject {
 public:
  ImplicitSurface(std::string expression_, const Material& m) : SceneObject(m), expression(std::move(expression_)) {}
  void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const override;

  std::string expression;
  ExpressionParameters parameters;
  kernel::ImplicitBound bound = kernel::ImplicitBound::Box;
  Vec3 box_a{-1}, box_b{1};          // bound: box corners
  Vec3 center{0};                    // bound: sphere
  Real radius = 1;
  kernel::RootMethod method = kernel::RootMethod::Lipschitz;
  Real max_gradient = Real(1.1);     // POV-Ray's default
  Real accuracy = Real(1e-3);
  Real step = 0;                     // march: 0 = accuracy·10
};

// The end-of-render report of implicit surfaces whose root finding met a steeper gradient than
// their max_gradient (holes are likely), or gave up on a ray: one line each, naming the object.
std::vector<std::string> implicit_warnings(const RenderScene& scene);

}  // namespace strahl
