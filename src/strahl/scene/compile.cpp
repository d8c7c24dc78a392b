#include <algorithm>
#include <cmath>
#include <utility>

#include "strahl/accel/embree_range.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/camera_build.h"
#include "strahl/scene/file_materials.h"
#include "strahl/scene/instances.h"
#include "strahl/scene/move_solid.h"
#include "strahl/scene/scene.h"
#include "strahl/scene/place_solid.h"
#include "strahl/scene/scene_warnings.h"
#include "strahl/scene/textures.h"
#include "strahl/scene/validate.h"
#include "strahl/util/cancel.h"

namespace strahl {

namespace {

// An orthonormal tangent frame of the plane, for 2D textures (checkerboard).
void plane_frame(const Vec3& n, Vec3& tangent, Vec3& bitangent) {
  const Vec3 a = std::fabs(n.x) < Real(0.9) ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  bitangent = normalize(cross(n, a));
  tangent = cross(bitangent, n);
}

}  // namespace

Camera build_camera(const CameraDescription& c, int nx, int ny) {
  validate::coordinates(c.position, c.loc, "camera position");
  validate::coordinates(c.look_at, c.loc, "camera look_at");
  validate::non_zero(c.up, c.loc, "camera up");
  const Vec3 view = c.look_at - c.position;
  if (max_abs_component(view) == 0) throw Error(c.loc, "camera position and look_at coincide");
  validate::length(validate::norm(view), c.loc, "camera distance from position to look_at");
  if (length_squared(cross(validate::direction(view), validate::direction(c.up))) < Real(1e-12))
    throw Error(c.loc, "camera up is parallel to the viewing direction");
  validate::non_negative(c.aperture, c.loc, "camera aperture");
  if (c.aperture > 0) validate::length(c.aperture, c.loc, "camera aperture");
  validate::non_negative(c.focus_distance, c.loc, "camera focus_distance");
  if (c.focus_distance > 0) validate::length(c.focus_distance, c.loc, "camera focus_distance");
  if (c.has_focus_point) validate::coordinates(c.focus_point, c.loc, "camera focus_point");
  validate::finite(c.focus_point, c.loc, "camera focus_point");
  validate::finite(c.shutter_open, c.loc, "shutter open");
  validate::finite(c.shutter_close, c.loc, "shutter close");
  if (c.shutter_close < c.shutter_open) throw Error(c.loc, "shutter close must not come before shutter open");
  Camera cam;
  cam.eye = c.position;
  cam.basis = Frame::look_at(c.position, c.look_at, validate::direction(c.up));
  cam.nx = nx;
  cam.ny = ny;
  cam.lens_radius = c.aperture;
  cam.focus_distance = c.has_focus_point ? dot(c.focus_point - c.position, -cam.basis.w)
                       : c.focus_distance > 0 ? c.focus_distance
                                              : length(c.look_at - c.position);
  if (c.aperture > 0 && !(cam.focus_distance > 0)) throw Error(c.loc, "camera focus_point must lie in front of the camera");
  cam.shutter_open = c.shutter_open;
  cam.shutter_close = c.shutter_close;
  if (c.explicit_image_plane) {
    for (Real v : {c.l, c.r, c.b, c.t}) validate::finite(v, c.loc, "image plane bound");
    validate::positive(c.d, c.loc, "image plane distance d");
    if (!(c.l < c.r) || !(c.b < c.t)) throw Error(c.loc, "image plane needs l < r and b < t");
    cam.l = c.l; cam.r = c.r; cam.b = c.b; cam.t = c.t; cam.d = c.d;
  } else {
    if (!(c.fov_degrees > 0 && c.fov_degrees < 180)) throw Error(c.loc, "camera fov must lie in (0, 180) degrees");
    const Real half = std::tan(c.fov_degrees * kPi / 360);
    const Real aspect = Real(nx) / Real(ny);
    cam.d = 1;
    if (c.fov_axis == CameraDescription::FovAxis::Horizontal) {
      cam.r = half; cam.t = half / aspect;
    } else {
      cam.t = half; cam.r = half * aspect;
    }
    cam.l = -cam.r;
    cam.b = -cam.t;
  }
  return cam;
}

namespace {

Vec3 apply(const Transform& t, const Vec3& p) { return t.linear() * p + t.translate; }

// Where point p is at shutter open (key 0) and close (key 1).
Vec3 moved(const Motion& m, const RenderScene& out, const Vec3& p, int key) {
  switch (m.kind) {
    case Motion::Kind::Velocity: return p + m.velocity() * (key == 0 ? out.camera.shutter_open : out.camera.shutter_close);
    case Motion::Kind::Keyframes: return apply(key == 0 ? m.from() : m.to(), p);
    case Motion::Kind::None: break;
  }
  return p;
}

// The linear part of the motion at a key, for normals (identity for a velocity).
Mat3 moved_linear(const Motion& m, int key) {
  return m.kind == Motion::Kind::Keyframes ? (key == 0 ? m.from() : m.to()).linear() : Mat3{};
}

// The scale of a map that scales evenly (a similarity: a sphere stays a sphere), else 0.
Real even_scale(const Transform& x) {
  if (!x.general()) {
    const Vec3 s = x.scale;
    return std::fabs(s.x) == std::fabs(s.y) && std::fabs(s.x) == std::fabs(s.z) ? std::fabs(s.x) : 0;
  }
  // Columns of one length, at right angles, to rounding (an axis-and-angle rotation's are).
  const Mat3 c = x.matrix().transposed();
  const Real l0 = length(c.row[0]), l1 = length(c.row[1]), l2 = length(c.row[2]);
  const Real tol = 1e-12 * l0;
  if (std::fabs(l1 - l0) <= tol && std::fabs(l2 - l0) <= tol && std::fabs(dot(c.row[0], c.row[1])) <= tol * l0 &&
      std::fabs(dot(c.row[0], c.row[2])) <= tol * l0 && std::fabs(dot(c.row[1], c.row[2])) <= tol * l0)
    return l0;
  return 0;
}

}  // namespace

void Sphere::compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const {
  if (placed()) {
    const Real even = even_scale(placement);
    if (even > 0) {
      // Still a sphere: its centre moved, its radius scaled.
      Sphere moved_sphere = *this;
      moved_sphere.placement = Transform{};
      moved_sphere.center = placement.linear() * center + placement.translate;
      moved_sphere.radius = radius * even;
      moved_sphere.compile_into(out, material_index, object_id);
      return;
    }
    // An ellipsoid: the sphere as a solid, placed (geometry/placement.h), and moved as solids are.
    validate::coordinates(center, loc, "sphere center");
    validate::positive(radius, loc, "sphere radius");
    validate::length(radius, loc, "sphere radius");
    validate::resolvable(radius, max_abs_component(center), loc, "sphere radius");
    out.solid_spheres.push_back({center, radius, material_index});
    out.solids.push_back({kernel::SolidKind::Sphere, std::uint32_t(out.solid_spheres.size() - 1), material_index});
    place_last_solid(out, affine_of(placement), loc);
    if (motion.moving()) move_last_solid(out, motion, loc);
    return;
  }
  validate::coordinates(center, loc, "sphere center");
  validate::positive(radius, loc, "sphere radius");
  validate::length(radius, loc, "sphere radius");
  validate::resolvable(radius, max_abs_component(center), loc, "sphere radius");
  if (motion.moving()) {
    validate_motion(motion, loc);
    // Keyframes transform the sphere in world space: its centre moves, and its radius scales
    // with the keyframe's even scale; an uneven one makes it an ellipsoid (below).
    Real radius_at[2] = {radius, radius};
    bool uneven = false;
    if (motion.kind == Motion::Kind::Keyframes) {
      for (int key = 0; key < 2 && !uneven; ++key) {
        const Real s = even_scale(key == 0 ? motion.from() : motion.to());
        uneven = !(s > 0);
        radius_at[key] = radius * s;
        if (uneven) break;
        validate::positive(radius_at[key], loc, "sphere radius after the motion scale");
        validate::length(radius_at[key], loc, "sphere radius after the motion scale");
      }
    }
    if (uneven || motion_turns(motion, out.camera, loc, "sphere")) {
      // Keyframes that turn it carry its centre on an arc (a blend of the keyed centres would
      // cut the arc's chord), and keys that scale it unevenly make an ellipsoid: it moves as a
      // solid sphere, as an ellipsoid does.
      out.solid_spheres.push_back({center, radius, material_index});
      out.solids.push_back({kernel::SolidKind::Sphere, std::uint32_t(out.solid_spheres.size() - 1), material_index});
      move_last_solid(out, motion, loc);
      return;
    }
    for (int key = 0; key < 2; ++key) {
      validate::coordinates(moved(motion, out, center, key), loc, "moving sphere center");
      validate::resolvable(radius_at[key], max_abs_component(moved(motion, out, center, key)), loc, "sphere radius");
    }
    out.moving_spheres.push_back({moved(motion, out, center, 0), moved(motion, out, center, 1), radius_at[0],
                                  radius_at[1], material_index});
    return;
  }
  out.spheres.push_back({center, radius, material_index});
}

void Plane::compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t) const {
  if (motion.moving()) throw Error(loc, "planes cannot move (motion is for spheres, triangles and meshes)");
  validate::non_zero(normal, loc, "plane normal");
  validate::finite(distance, loc, "plane distance");
  Vec3 n = normal;
  Real d = distance;
  if (placed()) {  // (a scene file's plane comes with its placement taken in already)
    place_plane(placement, n, d, loc);
    validate::non_zero(n, loc, "plane normal after the plane's transform");
    validate::finite(d, loc, "plane distance after the plane's transform");
  }
  kernel::Plane p;
  const Real len = validate::norm(n);  // without under- or overflow of N·N
  p.normal = validate::direction(n);
  p.distance = d / len;
  validate::coordinate(p.distance, loc, "plane distance");
  plane_frame(p.normal, p.tangent, p.bitangent);
  p.material = material_index;
  out.planes.push_back(p);
}

namespace {
// A mesh vertex where the mesh's transform (and motion) puts it: within the scale limits. Checked
// after the transform, so that a mesh scale of 1e300 is named, not an infinity or a lost mesh.
void mesh_coordinates(const Vec3& p, const FileLoc& loc) {
  const Real m = max_abs_component(p);
  if (!(m <= validate::kMaxCoordinate))  // also inf and nan
    throw Error(loc, "mesh vertex lands at a coordinate of " + validate::str(m) +
                         " after the mesh's scale/rotate/translate, beyond ±1e32 " + validate::kScaleLimits);
}

// Appends the triangle unless it is degenerate; returns whether it did.
bool push_triangle(RenderScene& out, const Vec3& a, const Vec3& b, const Vec3& c, std::uint32_t material,
                   std::int32_t normals, std::uint32_t object_id, const Vec3* keyed = nullptr,
                   std::int32_t texcoords = -1) {
  if (!(length_squared(cross(b - a, c - a)) > 0)) return false;
  if (keyed != nullptr) {  // moving: a, b, c at shutter open, then at close
    kernel::MovingTriangle t;
    for (int i = 0; i < 3; ++i) {
      t.p0[i] = keyed[i];
      t.p1[i] = keyed[3 + i];
    }
    t.material = material;
    t.normals = normals;
    t.object = object_id;
    t.texcoords = texcoords;
    out.moving_triangles.push_back(t);
    return true;
  }
  out.triangles.push_back({a, b, c, material, normals, object_id, texcoords});
  return true;
}
}  // namespace

void Triangle::compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const {
  Vec3 a = v0, b = v1, c = v2;
  if (placed()) place_triangle(placement, a, b, c, loc);  // (a scene file's comes placed already)
  validate::coordinates(a, loc, "triangle vertex");
  validate::coordinates(b, loc, "triangle vertex");
  validate::coordinates(c, loc, "triangle vertex");
  validate_motion(motion, loc);
  const Real longest = std::fmax(validate::norm(b - a), std::fmax(validate::norm(c - b), validate::norm(a - c)));
  if (longest > 0) {
    validate::length(longest, loc, "triangle's longest edge");
    validate::resolvable(longest, std::fmax(max_abs_component(a), std::fmax(max_abs_component(b), max_abs_component(c))),
                         loc, "triangle's longest edge");
  }
  if (motion.moving() && motion_turns(motion, out.camera, loc, "triangle")) {
    // Turned by its keyframes: it moves on arcs, as an instance of a group holding it unmoved.
    RenderScene group;
    if (!push_triangle(group, a, b, c, material_index, -1, object_id))
      throw Error(loc, "degenerate triangle (its vertices are collinear)");
    move_by_instance(out, std::move(group), moving_map(motion, out.camera, loc, "triangle"), loc);
    return;
  }
  Vec3 keyed[6];
  for (int key = 0; key < 2; ++key) {
    keyed[3 * key] = moved(motion, out, a, key);
    keyed[3 * key + 1] = moved(motion, out, b, key);
    keyed[3 * key + 2] = moved(motion, out, c, key);
  }
  if (motion.moving())
    for (const Vec3& v : keyed) validate::coordinates(v, loc, "moving triangle vertex");
  if (!push_triangle(out, a, b, c, material_index, -1, object_id, motion.moving() ? keyed : nullptr))
    throw Error(loc, "degenerate triangle (its vertices are collinear)");
}

namespace {
// The mesh `data` placed by `transform` and moved by `motion` (one that does not turn it), its
// faces as triangles or moving triangles; with `texcoords`, each face whose corners all have
// texture coordinates keeps them (for a uv-mapped image). A face with a file material
// (data.face_materials[f] = k ≥ 0) takes material file_material_base + k (0: none), the others
// material_index.
void compile_mesh(const MeshData& data, const Transform& transform, const Motion& motion, const FileLoc& loc,
                  RenderScene& out, std::uint32_t material_index, std::uint32_t object_id, bool texcoords,
                  std::uint32_t file_material_base) {
  validate::finite(transform.scale, loc, "mesh scale");
  validate::finite(transform.rotate_degrees, loc, "mesh rotate");
  validate::finite(transform.translate, loc, "mesh translate");
  const Mat3 m = transform.linear();
  if (m.determinant() == 0) throw Error(loc, "mesh scale must not be zero");
  const Mat3 normal_matrix = m.inverse().transposed();
  validate_motion(motion, loc);
  // Moving meshes keep two sets of vertex normals, at shutter open and close.
  // Keyframes act in the mesh's own coordinates, before its scale/rotate/translate (so a
  // rotation turns it about its own origin); a velocity moves it in world space.
  const Mat3 normal_key[2] = {(m * moved_linear(motion, 0)).inverse().transposed(),
                              (m * moved_linear(motion, 1)).inverse().transposed()};
  LargeArray<Vec3> positions(data.positions.size());
  LargeArray<Vec3> keyed_positions[2];
  for (std::size_t i = 0; i < positions.size(); ++i) {
    validate::finite(data.positions[i], loc, "mesh vertex");
    positions[i] = m * data.positions[i] + transform.translate;
    mesh_coordinates(positions[i], loc);
  }
  if (motion.moving()) {
    for (int key = 0; key < 2; ++key) {
      keyed_positions[key].resize(positions.size());
      for (std::size_t i = 0; i < positions.size(); ++i)
      {
        keyed_positions[key][i] = motion.kind == Motion::Kind::Keyframes
                                      ? m * moved(motion, out, data.positions[i], key) + transform.translate
                                      : moved(motion, out, positions[i], key);
        mesh_coordinates(keyed_positions[key][i], loc);
      }
    }
  }
  // A mirroring transform (negative determinant) would turn the faces inside out: swap two
  // vertices of each face so that front faces stay outside.
  const bool mirrored = m.determinant() < 0;
  // A moving face is a moving triangle with two sets of vertex normals (at open and at close).
  const std::size_t keys = motion.moving() ? 2 : 1;
  if (motion.moving()) out.moving_triangles.reserve(out.moving_triangles.size() + data.faces.size());
  else out.triangles.reserve(out.triangles.size() + data.faces.size());
  if (!data.normals.empty()) out.vertex_normals.reserve(out.vertex_normals.size() + keys * data.faces.size());
  texcoords = texcoords && !data.texcoords.empty();
  if (texcoords) out.vertex_texcoords.reserve(out.vertex_texcoords.size() + data.faces.size());
  std::size_t kept = 0;
  const bool file_materials = file_material_base != 0 && !data.face_materials.empty();
  for (std::size_t face = 0; face < data.faces.size(); ++face) {
    MeshData::Face f = data.faces[face];
    const std::uint32_t material =
        file_materials && data.face_materials[face] >= 0 ? file_material_base + std::uint32_t(data.face_materials[face])
                                                         : material_index;
    if (mirrored) {
      std::swap(f.v[1], f.v[2]);
      std::swap(f.n[1], f.n[2]);
      std::swap(f.t[1], f.t[2]);
    }
    for (std::uint32_t v : f.v)
      if (v >= positions.size()) throw Error(loc, "mesh face refers to a vertex that does not exist");
    std::int32_t normals = -1;
    if (f.n[0] >= 0 && f.n[1] >= 0 && f.n[2] >= 0) {
      for (std::int32_t n : f.n)
        if (std::size_t(n) >= data.normals.size()) throw Error(loc, "mesh face refers to a normal that does not exist");
      const auto xf = [&](std::int32_t n) {
        const Vec3 v = normal_matrix * data.normals[std::size_t(n)];
        return length_squared(v) > 0 && is_finite(v) ? normalize(v) : Vec3(0);
      };
      normals = static_cast<std::int32_t>(out.vertex_normals.size());
      if (motion.moving()) {
        for (const Mat3& nm : normal_key) {
          const auto xk = [&](std::int32_t n) {
            const Vec3 v = nm * data.normals[std::size_t(n)];
            return length_squared(v) > 0 && is_finite(v) ? normalize(v) : Vec3(0);
          };
          out.vertex_normals.push_back({xk(f.n[0]), xk(f.n[1]), xk(f.n[2])});
        }
      } else {
        out.vertex_normals.push_back({xf(f.n[0]), xf(f.n[1]), xf(f.n[2])});
      }
    }
    std::int32_t uvs = -1;
    if (texcoords && f.t[0] >= 0 && f.t[1] >= 0 && f.t[2] >= 0) {
      for (std::int32_t t : f.t)
        if (std::size_t(t) >= data.texcoords.size())
          throw Error(loc, "mesh face refers to a texture coordinate that does not exist");
      const Texcoord &t0 = data.texcoords[std::size_t(f.t[0])], &t1 = data.texcoords[std::size_t(f.t[1])],
                     &t2 = data.texcoords[std::size_t(f.t[2])];
      for (const Real c : {t0.u, t0.v, t1.u, t1.v, t2.u, t2.v})
        if (!std::isfinite(c)) throw Error(loc, "mesh texture coordinate is not a finite number");
      uvs = static_cast<std::int32_t>(out.vertex_texcoords.size());
      out.vertex_texcoords.push_back({t0.u, t0.v, t1.u, t1.v, t2.u, t2.v});
    }
    Vec3 keyed[6];
    if (motion.moving())
      for (int key = 0; key < 2; ++key)
        for (int i = 0; i < 3; ++i) keyed[3 * key + i] = keyed_positions[key][f.v[i]];
    if (push_triangle(out, positions[f.v[0]], positions[f.v[1]], positions[f.v[2]], material, normals,
                      object_id, motion.moving() ? keyed : nullptr, uvs)) {
      ++kept;
    } else {
      if (normals >= 0) {
        out.vertex_normals.pop_back();
        if (motion.moving()) out.vertex_normals.pop_back();
      }
      if (uvs >= 0) out.vertex_texcoords.pop_back();
    }
  }
  if (data.faces.empty()) throw Error(loc, "mesh has no faces");
  if (kept == 0)
    throw Error(loc, "mesh has no triangle with an area (all " + std::to_string(data.faces.size()) +
                         " are degenerate)");
}
}  // namespace

void Mesh::compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const {
  validate_motion(motion, loc);
  // (Whether the image is uv-mapped is not known here, in an instanced group's scene: the
  // texture coordinates are kept for any image, and the renderer asks the mapping.)
  bool uv_texture = material.texture != kNoTexture;
  // The file's materials follow the mesh's own in the scene's list (add_object_materials).
  const std::uint32_t file_material_base = material_index + 1;
  const bool by_file = !file_materials.empty();
  if (by_file && data.face_materials.size() != data.faces.size())
    throw Error(loc, "mesh face materials: one per face is needed");
  for (const Material& m : file_materials) uv_texture = uv_texture || m.texture != kNoTexture;
  if (by_file)
    for (const std::int32_t k : data.face_materials)
      if (k >= std::int32_t(file_materials.size()))
        throw Error(loc, "mesh face refers to a file material that does not exist");
  if (!(motion.moving() && motion_turns(motion, out.camera, loc, "mesh"))) {
    compile_mesh(data, transform, motion, loc, out, material_index, object_id, uv_texture, by_file ? file_material_base : 0);
    return;
  }
  // Keyframes that turn it (in its own coordinates, before its transform P) move its points on
  // arcs: it becomes an instance of a group holding it unmoved, carried by P·A(u).
  const Affine post = mesh_motion_post(transform, loc);
  RenderScene group;
  compile_mesh(data, Transform{}, Motion{}, loc, group, material_index, object_id, uv_texture, by_file ? file_material_base : 0);
  move_by_instance(out, std::move(group), moving_map(motion, out.camera, loc, "mesh", &post), loc);
}

// Checks the sampling settings; spp 0 means the N×N grid of `supersample`.
static SamplingSettings compile_sampling(const RenderSettings& s) {
  SamplingSettings out = s.sampling;
  validate::int_range(out.spp, 0, kMaxSpp, s.loc, "spp");
  if (out.spp == 0) out.spp = s.supersample * s.supersample;
  out.spp = effective_spp(out.sampler, out.spp);
  validate::in_range(out.filter.radius, kMinFilterRadius, kMaxFilterRadius, s.loc, "filter_radius");
  validate::int_range(out.adaptive_min, 1, kMaxSpp, s.loc, "adaptive_min");
  validate::positive(out.adaptive_threshold, s.loc, "adaptive_threshold");
  validate::finite(out.adaptive_threshold, s.loc, "adaptive_threshold");
  return out;
}

namespace {
// A spotlight's angles (degrees) and tightness, and the cosines the shading compares with.
void validate_spot_angles(Light& light, const FileLoc& loc) {
  validate::in_range(light.angle, 0, 90, loc, "spotlight angle");
  validate::in_range(light.falloff, 0, 90, loc, "spotlight falloff");
  validate::non_negative(light.tightness, loc, "spotlight tightness");
  light.cos_angle = std::cos(light.angle * kPi / 180);
  light.cos_falloff = std::cos(light.falloff * kPi / 180);
}

void validate_area_light(Light& light, const FileLoc& loc) {
  validate::coordinates(light.position, loc, light.kind == LightKind::Rect ? "light corner" : "light center");
  validate::int_range(light.samples, 1, 64, loc, "light samples");
  if (light.kind == LightKind::Rect) {
    validate::non_zero(light.edge_u, loc, "light edge_u");
    validate::non_zero(light.edge_v, loc, "light edge_v");
    validate::length(validate::norm(light.edge_u), loc, "light edge_u");
    validate::length(validate::norm(light.edge_v), loc, "light edge_v");
    const Real c = dot(validate::direction(light.edge_u), validate::direction(light.edge_v));
    if (std::fabs(c) > Real(1e-6)) throw Error(loc, "rect light edges must be perpendicular");
    light.normal = normalize(cross(validate::direction(light.edge_u), validate::direction(light.edge_v)));
  } else {
    validate::positive(light.radius, loc, "light radius");
    validate::length(light.radius, loc, "light radius");
    validate::resolvable(light.radius, max_abs_component(light.position), loc, "light radius");
    if (light.kind == LightKind::Disk) {
      validate::non_zero(light.normal, loc, "light normal");
      light.normal = validate::direction(light.normal);
    }
  }
}
}  // namespace

RenderScene compile(const Scene& scene) {
  const RenderSettings& s = scene.settings;
  validate::int_range(s.width, 1, 65536, s.loc, "width");
  validate::int_range(s.height, 1, 65536, s.loc, "height");
  // About 50 bytes a pixel for the film and image (render/film.h): refuse what would not fit in memory before allocating it.
  if (double(s.width) * s.height > double(1u << 28)) throw Error(s.loc, "resolution too large (over 268 million pixels)");
  validate::int_range(s.max_depth, 1, 64, s.loc, "max_depth");
  validate::int_range(s.supersample, 1, 64, s.loc, "supersample");
  validate::in_range(s.min_weight, 0, 1, s.loc, "min_weight");
  validate::int_range(s.ray_budget, 0, int(kMaxRayBudget), s.loc, "ray_budget");
  validate::non_negative(s.background, s.loc, "background");
  validate::non_negative(s.ambient_light, s.loc, "ambient_light");
  validate::positive(s.medium_ior, s.loc, "medium_ior");

  RenderScene out;
  out.camera = build_camera(scene.camera, s.width, s.height);
  out.settings = {s.max_depth, s.min_weight, s.background, s.ambient_light, s.medium_ior,
                  std::uint32_t(s.ray_budget), s.integrator};
  out.supersample = s.supersample;
  out.sampling = compile_sampling(s);

  compile_textures(scene, out);  // before the materials that name them
  compile_groups(scene, out);    // before the instances that place them
  std::uint32_t object_id = 0;  // (the camera, with its shutter, is built first: moving shapes need it)
  for (const auto& object : scene.objects()) {
    if ((object_id & 0x3ff) == 0) check_cancelled("build");
    add_texture_warning(*object, out);
    const std::uint32_t material_index = add_object_materials(*object, out);
    object->compile_into(out, material_index, object_id++);
  }
  // Bounded solids first (they enter the acceleration structure), unclipped quadrics and CSG
  // trees without bounds (an inverse, a union with such a quadric) after.
  const auto unbounded = [&](const kernel::Solid& k) {
    if (k.kind == kernel::SolidKind::Csg || k.kind == kernel::SolidKind::Placed) {
      const Bounds g = kernel::bounds(out.shapes(), k);
      return !(std::isfinite(g.lo.x) && std::isfinite(g.lo.y) && std::isfinite(g.lo.z) && std::isfinite(g.hi.x) &&
               std::isfinite(g.hi.y) && std::isfinite(g.hi.z));
    }
    return k.kind == kernel::SolidKind::Quadric && !out.quadrics[k.index].clipped;
  };
  std::stable_partition(out.solids.begin(), out.solids.end(), [&](const kernel::Solid& k) { return !unbounded(k); });
  out.bounded_solid_count =
      static_cast<std::uint32_t>(std::count_if(out.solids.begin(), out.solids.end(), [&](const kernel::Solid& k) {
        return !unbounded(k);
      }));
  for (std::size_t i = 0; i < scene.lights().size(); ++i) {
    Light light = scene.lights()[i];
    const FileLoc& loc = scene.light_locs()[i];
    validate::non_negative(light.radiance, loc, "light colour × intensity");
    validate::non_negative(light.fade_distance, loc, "light fade_distance");
    validate::non_negative(light.fade_power, loc, "light fade_power");
    if (light.fade_power > 0 && light.kind != LightKind::Point && light.kind != LightKind::Spot)
      throw Error(loc, "only point and spot lights fade with distance");
    if (light.fade_power > 0 && !(light.fade_distance > 0))
      throw Error(loc, "a light's fade_power needs a positive fade_distance (the distance where the fade is 1)");
    if (light.kind == LightKind::Point) {
      validate::coordinates(light.position, loc, "light position");
    } else if (light.kind == LightKind::Directional) {
      validate::non_zero(light.direction, loc, "light direction");
      light.direction = validate::direction(light.direction);
    } else if (light.kind == LightKind::Spot) {
      validate::coordinates(light.position, loc, "light position");
      validate::non_zero(light.direction, loc, "spotlight direction");
      light.direction = validate::direction(light.direction);
      validate_spot_angles(light, loc);
    } else {
      validate_area_light(light, loc);
    }
    out.lights.push_back(light);
  }
  out.warnings.insert(out.warnings.begin(), scene.warnings.begin(), scene.warnings.end());  // before compile()'s own
  add_light_warnings(scene, out);
  check_cancelled("build");
  out.accel = build_accel(s.accel, out.primitives());
  check_cancelled("build");
#if defined(STRAHL_HAVE_EMBREE)
  if (s.accel == AccelKind::Embree && out.accel.kind != AccelKind::Embree && !embree_misfit(out.primitives()).empty())
    out.warnings.push_back(s.loc.str() + (s.loc.file.empty() ? "" : ": ") + "accel embree cannot hold this scene, " +
                           embree_misfit(out.primitives()) + "; rendering with bvh instead");
#endif
  out.moving_bvh = build_motion_bvh(out.moving_spheres, out.moving_triangles, out.moving_solids, out.moving_instances);
  build_instance_bvh(out);
  return out;
}

Scene lecture_scene() {
  Scene scene;
  scene.addSceneObject(new Plane(Vec3(0.0, 1.0, 0.0), 0.0, Vec3(0.3, 0.3, 0.3)));
  scene.addSceneObject(new Sphere(Vec3(0.05, 0.3, 0.0), 0.3, Vec3(0.8, 0.2, 0.2)));
  scene.addSceneObject(new Sphere(Vec3(0.4, 0.1, 0.1), 0.1, Vec3(0.0, 1.0, 0.0)));
  scene.addSceneObject(new Sphere(Vec3(-0.35, 0.25, -0.15), 0.25, Vec3(0.5, 0.5, 0.1)));
  scene.addSceneObject(new Sphere(Vec3(-0.35, 0.15, 0.3), 0.15, Vec3(0.0, 0.0, 1.0)));
  scene.addSceneObject(new Sphere(Vec3(0.15, 0.6, -1.0), 0.6, Vec3(0.2, 0.4, 0.5)));
  scene.addLightSource(Vec3(1.0, 1.5, 1.0));
  return scene;
}

}  // namespace strahl
