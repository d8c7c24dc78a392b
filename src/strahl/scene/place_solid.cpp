// place_last_solid, place_plane and place_triangle (scene/place_solid.h).

#include "strahl/scene/place_solid.h"

#include <cmath>
#include <utility>

#include "strahl/render/render_scene.h"
#include "strahl/scene/validate.h"

namespace strahl {

void place_last_solid(RenderScene& out, const Affine& to_world, const FileLoc& loc) {
  kernel::Solid handle = out.solids.back();
  kernel::Solid shape = handle;
  Affine total = to_world;
  if (handle.kind == kernel::SolidKind::Placed) {
    const kernel::PlacedSolid& x = out.placed[handle.index];
    Mat3 to_object;
    for (int i = 0; i < 3; ++i) to_object.row[i] = x.to_object.row[i];
    total = compose(to_world, Affine{to_object.inverse(), x.to_object.translate});
    shape = x.shape;
  }
  const Real det = total.m.determinant();
  if (!(std::fabs(det) > 0) || !std::isfinite(det))
    throw Error(loc, "the transform is singular (a scale of 0 flattens the object)");
  kernel::PlacedSolid p;
  const Mat3 inv = total.m.inverse();
  for (int i = 0; i < 3; ++i) p.to_object.row[i] = inv.row[i];
  p.to_object.translate = total.t;
  validate::finite(total.t, loc, "translate");
  p.shape = shape;
  // World bounds: the object bounds' eight corners carried over (infinite stays infinite).
  const Bounds b = kernel::bounds(out.shapes(), shape);
  Bounds w;
  const bool finite = std::isfinite(b.lo.x) && std::isfinite(b.lo.y) && std::isfinite(b.lo.z) &&
                      std::isfinite(b.hi.x) && std::isfinite(b.hi.y) && std::isfinite(b.hi.z);
  if (finite) {
    for (int c = 0; c < 8; ++c) {
      const Vec3 corner((c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z);
      w.extend(total.m * corner + total.t);
    }
  } else {
    w.extend(Vec3(-kInfinity));
    w.extend(Vec3(kInfinity));
  }
  p.lo = w.lo;
  p.hi = w.hi;
  if (handle.kind == kernel::SolidKind::Placed) {
    out.placed[handle.index] = p;
  } else {
    out.placed.push_back(p);
    handle = {kernel::SolidKind::Placed, static_cast<std::uint32_t>(out.placed.size() - 1), handle.material};
  }
  out.solids.back() = handle;
}

namespace {
// The map's linear part, refused where it is singular.
Mat3 regular_linear(const Transform& x, const FileLoc& loc) {
  const Mat3 m = x.linear();
  const Real det = m.determinant();
  if (!(std::fabs(det) > 0) || !std::isfinite(det))
    throw Error(loc, "the transform is singular (a scale of 0 flattens the object)");
  return m;
}
}  // namespace

void place_plane(const Transform& x, Vec3& normal, Real& distance, const FileLoc& loc) {
  const Mat3 m = regular_linear(x, loc);
  const Vec3 n = validate::direction(normal);
  const Vec3 point = n * (distance / validate::norm(normal));
  normal = m.inverse().transposed() * n;
  distance = dot(normal, m * point + x.translate);
}

void place_triangle(const Transform& x, Vec3& a, Vec3& b, Vec3& c, const FileLoc& loc) {
  const Mat3 m = regular_linear(x, loc);
  a = m * a + x.translate;
  b = m * b + x.translate;
  c = m * c + x.translate;
  if (m.determinant() < 0) std::swap(b, c);
}

}  // namespace strahl
