#include "strahl/scene/scene_warnings.h"

#include <algorithm>
#include <cmath>

#include "strahl/scene/shape_bounds.h"
#include "strahl/scene/validate.h"
#include "strahl/shading/area_light.h"

namespace strahl {

namespace {

// The box around every bounded shape (spheres, triangles, bounded solids), moving ones over
// their whole path.
Bounds bounded_shapes(const RenderScene& s) {
  Bounds b = bounds_of(s.primitives());
  for (const kernel::MovingSphere& m : s.moving_spheres) extend(b, kernel::swept_bounds(m));
  for (const kernel::MovingTriangle& m : s.moving_triangles) extend(b, kernel::swept_bounds(m));
  for (const kernel::MovingSolid& m : s.moving_solids) extend(b, kernel::swept_bounds(m));
  for (const kernel::MovingInstance& m : s.moving_instances) extend(b, kernel::swept_bounds(m));
  for (const Bounds& p : s.instance_bounds) extend(b, p);
  return b;
}

// Does some object reach into the open half-space in front of the plane through p with normal n?
bool anything_in_front(const RenderScene& s, const Bounds& shapes, const Vec3& p, const Vec3& n) {
  if (!shapes.empty()) {
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 c((corner & 1) ? shapes.hi.x : shapes.lo.x, (corner & 2) ? shapes.hi.y : shapes.lo.y,
                   (corner & 4) ? shapes.hi.z : shapes.lo.z);
      if (dot(c - p, n) > 0) return true;
    }
  }
  if (s.solids.size() > s.bounded_solid_count) return true;  // an unclipped quadric may reach anywhere
  for (const kernel::Plane& plane : s.planes) {
    // A plane not parallel to the light's reaches both sides; a parallel one lies on one side.
    if (length_squared(cross(plane.normal, n)) > Real(1e-12)) return true;
    if (dot(plane.normal, n) * (plane.distance - dot(plane.normal, p)) > 0) return true;
  }
  return false;
}

// Distance from p to the box (0 inside it or when there is no box).
Real distance_to(const Bounds& b, const Vec3& p) {
  if (b.empty()) return 0;
  const Vec3 d(std::fmax(Real(0), std::fmax(b.lo.x - p.x, p.x - b.hi.x)),
               std::fmax(Real(0), std::fmax(b.lo.y - p.y, p.y - b.hi.y)),
               std::fmax(Real(0), std::fmax(b.lo.z - p.z, p.z - b.hi.z)));
  const Real m = max_abs_component(d);
  return m > 0 ? length(d / m) * m : 0;
}

// The most a light can add to a pixel (white = 1, before the material's factors): a point or
// directional light its radiance; an area light at most its radiance L (a surface it covers
// entirely), and no more than L·A⊥/(π·D²) at distance D from the nearest bounded shape.
Real brightest(const Light& l, const Bounds& shapes) {
  const Real peak = std::fmax(l.radiance.x, std::fmax(l.radiance.y, l.radiance.z));
  if (!l.is_area()) return peak;
  const Real d = distance_to(shapes, l.position);
  if (!(d > 0)) return peak;
  const Real projected = l.kind == LightKind::Sphere ? kPi * l.radius * l.radius : area_light_area(l);
  const Real r = d / std::sqrt(projected / kPi);  // distance in units of the light's size
  return std::fmin(peak, peak / (r * r));
}

std::string where(const FileLoc& loc) { return loc.file.empty() ? std::string() : loc.str() + ": "; }

}  // namespace

void add_texture_warning(const SceneObject& object, RenderScene& out) {
  const std::uint32_t t = object.material.texture;
  if (t >= out.textures.size() || out.textures[t].mapping != ImageMapping::UV) return;  // (also kNoTexture)
  const auto* mesh = dynamic_cast<const Mesh*>(&object);
  const auto mapped = [](const MeshData::Face& f) { return f.t[0] >= 0 && f.t[1] >= 0 && f.t[2] >= 0; };
  if (mesh != nullptr && std::any_of(mesh->data.faces.begin(), mesh->data.faces.end(), mapped)) return;
  out.warnings.push_back(where(object.loc) +
                         (mesh != nullptr ? "the mesh has no texture coordinates (OBJ vt, PLY u and v)"
                                          : "only meshes have texture coordinates") +
                         ": its uv-mapped image is read at the point, as planar");
}

void add_light_warnings(const Scene& scene, RenderScene& out) {
  const Bounds shapes = bounded_shapes(out);
  for (std::size_t i = 0; i < out.lights.size() && i < scene.light_locs().size(); ++i) {
    const Light& l = out.lights[i];
    const std::string at = where(scene.light_locs()[i]);
    const char* name = l.kind == LightKind::Rect ? "rect light" : l.kind == LightKind::Disk ? "disk light" : nullptr;
    if (name != nullptr && !anything_in_front(out, shapes, l.position, l.normal)) {
      out.warnings.push_back(at + "the " + name + " emits towards (" + validate::str(l.normal.x) + ", " +
                             validate::str(l.normal.y) + ", " + validate::str(l.normal.z) +
                             "), away from every object: it lights nothing" +
                             (l.kind == LightKind::Rect ? " (swap edge_u and edge_v to turn it round)"
                                                        : " (turn its normal round)"));
      continue;
    }
    const Real most = brightest(l, shapes);
    if (most < kFaintLight)
      out.warnings.push_back(at + "the light adds at most " + validate::str(most) +
                             " to any pixel (white is 1): too faint or too small to show");
  }
}

}  // namespace strahl
