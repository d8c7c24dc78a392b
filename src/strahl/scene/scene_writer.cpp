#include "strahl/scene/scene_writer.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include "strahl/image/image_io.h"
#include "strahl/image/output_file.h"
#include "strahl/scene/csg.h"
#include "strahl/scene/instances.h"
#include "strahl/scene/solids.h"
#include "strahl/shading/light.h"

namespace strahl {

namespace {

// Text built up line by line; numbers in std::to_chars's shortest form, which reads back
// (strtod, as yaml-cpp does) to the very same double.
class Writer {
 public:
  std::string text;

  void line(int indent, const std::string& s) {
    text.append(std::size_t(indent), ' ');
    text += s;
    text += '\n';
  }
  static std::string num(Real v, const std::string& what) {
    if (!std::isfinite(v)) throw Error("cannot write " + what + ": it is not a finite number");
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, double(v));
    return std::string(buf, r.ptr);
  }
  static std::string integer(long long v) { return std::to_string(v); }
  static std::string vec(const Vec3& v, const std::string& what) {
    return "[" + num(v.x, what) + ", " + num(v.y, what) + ", " + num(v.z, what) + "]";
  }
  static std::string boolean(bool b) { return b ? "true" : "false"; }
  // A YAML double-quoted scalar that reads back as `text`, whatever its characters.
  static std::string quoted(const std::string& text) {
    std::string q = "\"";
    for (const char ch : text) {
      const auto c = static_cast<unsigned char>(ch);
      if (ch == '"' || ch == '\\') {
        q += '\\';
        q += ch;
      } else if (c < 0x20 || c == 0x7f) {
        static const char* const kHex = "0123456789abcdef";
        q += "\\x";
        q += kHex[c >> 4];
        q += kHex[c & 15];
      } else {
        q += ch;
      }
    }
    return q + "\"";
  }
  // Another writer's lines, each indented by `indent` more.
  void lines(int indent, const Writer& sub) {
    std::size_t start = 0;
    for (std::size_t end; (end = sub.text.find('\n', start)) != std::string::npos; start = end + 1)
      line(indent, sub.text.substr(start, end - start));
  }
};

// Each picture is written once, numbered in the order the scene's textures first use it
// (textures sharing a picture share its file, and so its pixels when read back).
std::string texture_file(const std::string& stem, std::uint32_t picture) {
  return stem + ".texture" + std::to_string(picture) + ".pfm";
}
std::vector<std::uint32_t> picture_numbers(const Scene& scene, std::vector<const Image*>* pictures = nullptr) {
  std::map<const Image*, std::uint32_t> number;
  std::vector<std::uint32_t> out;
  for (const ImageTexture& t : scene.textures()) {
    const auto [it, fresh] = number.try_emplace(t.image.get(), std::uint32_t(number.size()));
    if (fresh && pictures != nullptr) pictures->push_back(t.image.get());
    out.push_back(it->second);
  }
  return out;
}

std::string placement_keys(const Transform& t, const std::string& what);

// An image texture in place; its picture is the PFM file save_scene writes beside the scene.
std::string image_map(const ImageTexture& t, const std::string& file) {
  return "{file: " + Writer::quoted(file) + ", mapping: " + image_mapping_name(t.mapping) +
         ", interpolate: " + image_interpolate_name(t.bilinear) + ", once: " + Writer::boolean(t.once) + ", " +
         placement_keys(t.placement, "image") + "}";
}

// What a material's texture is written as: the scene's textures and the file of each one's picture.
struct TextureFiles {
  const std::vector<ImageTexture>& textures;
  std::vector<std::string> file;  // per texture
  TextureFiles(const Scene& scene, const std::string& stem) : textures(scene.textures()) {
    for (const std::uint32_t picture : picture_numbers(scene)) file.push_back(texture_file(stem, picture));
  }
};

std::string material_map(const Material& m, const TextureFiles& tx) {
  using W = Writer;
  std::string s = "{color: " + W::vec(m.color, "material color") + ", ambient: " + W::num(m.ambient, "ambient") +
                  ", diffuse: " + W::num(m.diffuse, "diffuse") + ", specular: " + W::vec(m.specular, "specular") +
                  ", shininess: " + W::num(m.shininess, "shininess") +
                  ", reflectivity: " + W::num(m.reflectivity, "reflectivity") +
                  ", transparency: " + W::num(m.transparency, "transparency") + ", ior: " + W::num(m.ior, "ior") +
                  ", fresnel: " + W::boolean(m.fresnel) + ", filter: " + W::boolean(m.filter) +
                  ", roughness: " + W::num(m.roughness, "roughness");
  if (!is_black(m.emission)) s += ", emission: " + W::vec(m.emission, "emission");
  // (checker_color without a checker has no effect and no key; it is not written.)
  if (m.checker_size > 0)
    s += ", checker: {size: " + W::num(m.checker_size, "checker size") +
         ", color: " + W::vec(m.checker_color, "checker color") + "}";
  if (m.texture != kNoTexture) {
    if (m.texture >= tx.textures.size()) throw Error(FileLoc{}, "cannot write a material whose texture the scene does not have");
    s += ", image: " + image_map(tx.textures[m.texture], tx.file[m.texture]);
  }
  return s + "}";
}

std::string matrix_rows(const Transform& t, const std::string& what);

std::string placement_keys(const Transform& t, const std::string& what) {
  if (t.general()) return "matrix: " + matrix_rows(t, what + " matrix");
  return "scale: " + Writer::vec(t.scale, what + " scale") + ", rotate: " + Writer::vec(t.rotate_degrees, what + " rotate") +
         ", translate: " + Writer::vec(t.translate, what + " translate");
}

std::string transform_map(const Transform& t, const std::string& what) { return "{" + placement_keys(t, what) + "}"; }

void motion(Writer& w, const Motion& m) {
  std::string keys;
  switch (m.kind) {
    case Motion::Kind::None: break;
    case Motion::Kind::Velocity: keys = "velocity: " + Writer::vec(m.velocity(), "motion velocity"); break;
    case Motion::Kind::Keyframes:
      keys = "from: " + transform_map(m.from(), "motion") + ", to: " + transform_map(m.to(), "motion");
      break;
  }
  if (m.spins())
    keys += std::string(keys.empty() ? "" : ", ") + "spin: {axis: " + Writer::vec(m.spin().axis, "motion spin axis") +
            ", angle: " + Writer::num(m.spin().angle, "motion spin angle") +
            ", center: " + Writer::vec(m.spin().center, "motion spin center") + "}";
  if (!keys.empty()) w.line(4, "motion: {" + keys + "}");
}

// A general transform (Transform::general) as its 3×4 matrix.
std::string matrix_rows(const Transform& t, const std::string& what) {
  const Mat3& m = t.matrix();
  std::string rows;
  for (int r = 0; r < 3; ++r)
    rows += std::string(r ? ", " : "") + "[" + Writer::num(m.row[r].x, what) + ", " + Writer::num(m.row[r].y, what) + ", " +
            Writer::num(m.row[r].z, what) + ", " + Writer::num(t.translate[r], what) + "]";
  return "[" + rows + "]";
}
void matrix(Writer& w, const Transform& t, const std::string& what) { w.line(4, "matrix: " + matrix_rows(t, what)); }

// A mesh in its file's materials (glTF, OBJ) names that file again (its data and materials are the
// file's); any other mesh names the OBJ file save_scene writes for it.
void mesh(Writer& w, const Mesh& mesh, const std::string& file) {
  using W = Writer;
  if (mesh.file_materials.empty()) {
    w.line(4, "file: " + file);
  } else {
    if (mesh.file_materials_source.empty())
      throw Error(mesh.loc, "cannot write a mesh in file materials that were not read from a file");
    w.line(4, "file: " + W::quoted(mesh.file_materials_source.string()));
    w.line(4, "file_materials: true");
  }
  if (mesh.transform.general()) return matrix(w, mesh.transform, "mesh matrix");
  w.line(4, "scale: " + W::vec(mesh.transform.scale, "mesh scale"));
  w.line(4, "rotate: " + W::vec(mesh.transform.rotate_degrees, "mesh rotate"));
  w.line(4, "translate: " + W::vec(mesh.transform.translate, "mesh translate"));
}

std::string mesh_file(const std::string& stem, int index) { return stem + ".mesh" + std::to_string(index) + ".obj"; }

std::string box_map(const Vec3& a, const Vec3& b, const std::string& what) {
  return "{type: box, corners: [" + Writer::vec(a, what) + ", " + Writer::vec(b, what) + "]}";
}

// scale, rotate and translate (or the matrix) of a placed object.
void placement(Writer& w, const SceneObject& o) {
  if (!o.placed()) return;
  if (o.placement.general()) return matrix(w, o.placement, "matrix");
  w.line(4, "scale: " + Writer::vec(o.placement.scale, "scale"));
  w.line(4, "rotate: " + Writer::vec(o.placement.rotate_degrees, "rotate"));
  w.line(4, "translate: " + Writer::vec(o.placement.translate, "translate"));
}

// The solids of scene/solids.h; false for anything else.
bool solid(Writer& w, const SceneObject& o) {
  using W = Writer;
  if (const auto* b = dynamic_cast<const Box*>(&o)) {
    w.line(2, "- type: box");
    w.line(4, "corners: [" + W::vec(b->corner_a, "box corner") + ", " + W::vec(b->corner_b, "box corner") + "]");
  } else if (const auto* c = dynamic_cast<const Cone*>(&o)) {
    w.line(2, c->is_cylinder ? "- type: cylinder" : "- type: cone");
    w.line(4, "base: " + W::vec(c->base, "base"));
    w.line(4, "cap: " + W::vec(c->cap, "cap"));
    if (c->is_cylinder) {
      w.line(4, "radius: " + W::num(c->base_radius, "cylinder radius"));
    } else {
      w.line(4, "base_radius: " + W::num(c->base_radius, "cone base_radius"));
      w.line(4, "cap_radius: " + W::num(c->cap_radius, "cone cap_radius"));
    }
    w.line(4, "open: " + W::boolean(c->open));
  } else if (const auto* d = dynamic_cast<const Disk*>(&o)) {
    w.line(2, "- type: disk");
    w.line(4, "center: " + W::vec(d->center, "disk center"));
    w.line(4, "normal: " + W::vec(d->normal, "disk normal"));
    w.line(4, "radius: " + W::num(d->radius, "disk radius"));
  } else if (const auto* t = dynamic_cast<const Torus*>(&o)) {
    w.line(2, "- type: torus");
    w.line(4, "center: " + W::vec(t->center, "torus center"));
    w.line(4, "axis: " + W::vec(t->axis, "torus axis"));
    w.line(4, "major_radius: " + W::num(t->major, "torus major_radius"));
    w.line(4, "minor_radius: " + W::num(t->minor, "torus minor_radius"));
  } else if (const auto* q = dynamic_cast<const Quadric*>(&o)) {
    w.line(2, "- type: quadric");
    std::string k;
    for (Real v : q->coefficients) k += (k.empty() ? "" : ", ") + W::num(v, "quadric coefficient");
    w.line(4, "coefficients: [" + k + "]");
    if (q->clip) w.line(4, "clipped_by: " + box_map(q->clip->a, q->clip->b, "quadric clip box corner"));
  } else if (const auto* f = dynamic_cast<const ImplicitSurface*>(&o)) {
    w.line(2, "- type: implicit");
    std::string quoted = "\"";  // a YAML double-quoted scalar
    for (const char ch : f->expression) {
      if (ch == '"' || ch == '\\') quoted += '\\';
      if (ch == '\n' || ch == '\t' || ch == '\r') {
        quoted += ' ';
        continue;
      }
      quoted += ch;
    }
    w.line(4, "expression: " + quoted + "\"");
    if (!f->parameters.empty()) {
      std::string p;
      for (const auto& [name, value] : f->parameters)
        p += (p.empty() ? "" : ", ") + name + ": " + W::num(value, "implicit parameter " + name);
      w.line(4, "parameters: {" + p + "}");
    }
    if (f->bound == kernel::ImplicitBound::Box)
      w.line(4, "contained_by: " + box_map(f->box_a, f->box_b, "implicit contained_by corner"));
    else
      w.line(4, "contained_by: {type: sphere, center: " + W::vec(f->center, "implicit contained_by center") +
                    ", radius: " + W::num(f->radius, "implicit contained_by radius") + "}");
    const char* method = f->method == kernel::RootMethod::SphereTrace ? "distance"
                         : f->method == kernel::RootMethod::March     ? "march"
                                                                      : "lipschitz";
    w.line(4, std::string("method: ") + method);
    w.line(4, "max_gradient: " + W::num(f->max_gradient, "implicit max_gradient"));
    w.line(4, "accuracy: " + W::num(f->accuracy, "implicit accuracy"));
    if (f->method == kernel::RootMethod::March && f->step > 0) w.line(4, "step: " + W::num(f->step, "implicit step"));
  } else {
    return false;
  }
  placement(w, o);
  return true;
}

void sphere(Writer& w, const Sphere& s) {
  w.line(2, "- type: sphere");
  w.line(4, "center: " + Writer::vec(s.center, "sphere center"));
  w.line(4, "radius: " + Writer::num(s.radius, "sphere radius"));
  placement(w, s);
}

// A CSG node (scene/csg.h): its type and its objects, each written as at the top level (without
// a material: the outermost node's applies) and indented under `objects:`.
void csg(Writer& w, const Csg& c) {
  w.line(2, std::string("- type: ") + csg_operation_name(c.operation));
  placement(w, c);
  w.line(4, "objects:");
  for (const auto& child : c.children) {
    Writer sub;
    if (const auto* n = dynamic_cast<const Csg*>(child.get())) csg(sub, *n);
    else if (const auto* s = dynamic_cast<const Sphere*>(child.get())) sphere(sub, *s);
    else if (!solid(sub, *child)) throw Error(child->loc, "cannot write this kind of object as an object of a CSG");
    w.lines(4, sub);
  }
}

// One object; `groups`: the scene's, which instances name.
void object(Writer& w, const SceneObject& o, const std::vector<ObjectGroup>& groups, const TextureFiles& tx,
            const std::string& mesh_stem, int& meshes) {
  using W = Writer;
  if (const auto* in = dynamic_cast<const Instance*>(&o)) {  // (no material)
    if (in->group >= groups.size()) throw Error(in->loc, "cannot write an instance of a group the scene does not have");
    w.line(2, "- type: instance");
    w.line(4, "of: " + W::quoted(groups[in->group].name));
    placement(w, *in);
    motion(w, in->motion);
    return;
  }
  if (const auto* s = dynamic_cast<const Sphere*>(&o)) {
    sphere(w, *s);
  } else if (const auto* c = dynamic_cast<const Csg*>(&o)) {
    csg(w, *c);
  } else if (const auto* p = dynamic_cast<const Plane*>(&o)) {
    w.line(2, "- type: plane");
    w.line(4, "normal: " + W::vec(p->normal, "plane normal"));
    w.line(4, "distance: " + W::num(p->distance, "plane distance"));
    placement(w, *p);
  } else if (const auto* t = dynamic_cast<const Triangle*>(&o)) {
    w.line(2, "- type: triangle");
    w.line(4, "vertices: [" + W::vec(t->v0, "triangle vertex") + ", " + W::vec(t->v1, "triangle vertex") + ", " +
                  W::vec(t->v2, "triangle vertex") + "]");
    placement(w, *t);
  } else if (const auto* m = dynamic_cast<const Mesh*>(&o)) {
    w.line(2, "- type: mesh");
    mesh(w, *m, mesh_file(mesh_stem, meshes++));
  } else if (!solid(w, o)) {
    throw Error(o.loc, "cannot write this kind of object to a scene file");
  }
  w.line(4, "material: " + material_map(o.material, tx));
  motion(w, o.motion);
}

// Lights as their radiance: colour = radiance, intensity 1 (the loader multiplies the two).
void light(Writer& w, const Light& l) {
  using W = Writer;
  const std::string fade = l.fade_power > 0 ? ", fade_distance: " + W::num(l.fade_distance, "light fade_distance") +
                                                  ", fade_power: " + W::num(l.fade_power, "light fade_power")
                                            : std::string();
  const std::string color = ", color: " + W::vec(l.radiance, "light color") + fade;
  switch (l.kind) {
    case LightKind::Point: w.line(2, "- {type: point, position: " + W::vec(l.position, "light position") + color + "}"); return;
    case LightKind::Directional:
      w.line(2, "- {type: directional, direction: " + W::vec(l.direction, "light direction") + color + "}");
      return;
    case LightKind::Spot:
      w.line(2, "- {type: spot, position: " + W::vec(l.position, "light position") + ", direction: " +
                    W::vec(l.direction, "spotlight direction") + ", angle: " + W::num(l.angle, "spotlight angle") +
                    ", falloff: " + W::num(l.falloff, "spotlight falloff") +
                    ", tightness: " + W::num(l.tightness, "spotlight tightness") + color + "}");
      return;
    case LightKind::Rect:
      w.line(2, "- {type: rect, corner: " + W::vec(l.position, "light corner") + ", edge_u: " + W::vec(l.edge_u, "edge_u") +
                    ", edge_v: " + W::vec(l.edge_v, "edge_v") + color + ", samples: " + W::integer(l.samples) + "}");
      return;
    case LightKind::Disk:
      w.line(2, "- {type: disk, center: " + W::vec(l.position, "light center") + ", normal: " + W::vec(l.normal, "light normal") +
                    ", radius: " + W::num(l.radius, "light radius") + color + ", samples: " + W::integer(l.samples) + "}");
      return;
    case LightKind::Sphere:
      w.line(2, "- {type: sphere, center: " + W::vec(l.position, "light center") + ", radius: " + W::num(l.radius, "light radius") +
                    color + ", samples: " + W::integer(l.samples) + "}");
      return;
  }
}

void camera(Writer& w, const CameraDescription& c) {
  using W = Writer;
  w.line(0, "camera:");
  w.line(2, "position: " + W::vec(c.position, "camera position"));
  w.line(2, "look_at: " + W::vec(c.look_at, "camera look_at"));
  w.line(2, "up: " + W::vec(c.up, "camera up"));
  if (c.explicit_image_plane) {
    w.line(2, "image_plane: {l: " + W::num(c.l, "l") + ", r: " + W::num(c.r, "r") + ", b: " + W::num(c.b, "b") +
                  ", t: " + W::num(c.t, "t") + ", d: " + W::num(c.d, "d") + "}");
  } else {
    w.line(2, "fov: " + W::num(c.fov_degrees, "fov"));
    w.line(2, std::string("fov_axis: ") +
                  (c.fov_axis == CameraDescription::FovAxis::Horizontal ? "horizontal" : "vertical"));
  }
  w.line(2, "aperture: " + W::num(c.aperture, "aperture"));
  if (c.has_focus_point) w.line(2, "focus_point: " + W::vec(c.focus_point, "focus_point"));
  else if (c.focus_distance > 0) w.line(2, "focus_distance: " + W::num(c.focus_distance, "focus_distance"));
  w.line(2, "shutter: [" + W::num(c.shutter_open, "shutter open") + ", " + W::num(c.shutter_close, "shutter close") + "]");
}

void render_settings(Writer& w, const RenderSettings& s) {
  using W = Writer;
  const SamplingSettings& p = s.sampling;
  w.line(0, "render:");
  w.line(2, "width: " + W::integer(s.width));
  w.line(2, "height: " + W::integer(s.height));
  w.line(2, "max_depth: " + W::integer(s.max_depth));
  w.line(2, "min_weight: " + W::num(s.min_weight, "min_weight"));
  w.line(2, "ray_budget: " + W::integer(s.ray_budget));
  w.line(2, "supersample: " + W::integer(s.supersample));
  w.line(2, "background: " + W::vec(s.background, "background"));
  w.line(2, "ambient_light: " + W::vec(s.ambient_light, "ambient_light"));
  w.line(2, "medium_ior: " + W::num(s.medium_ior, "medium_ior"));
  w.line(2, std::string("integrator: ") + integrator_name(s.integrator));
  w.line(2, "accel: " + std::string(accel_name(s.accel)));
  w.line(2, std::string("sampler: ") + sampler_name(p.sampler));
  if (p.spp != 0) w.line(2, "spp: " + W::integer(p.spp));  // 0: supersample² (the key's default)
  w.line(2, "seed: " + std::to_string(p.seed));
  w.line(2, std::string("filter: ") + filter_name(p.filter.kind));
  w.line(2, "filter_radius: " + W::num(p.filter.radius, "filter_radius"));
  w.line(2, "adaptive_min: " + W::integer(p.adaptive_min));
  w.line(2, "adaptive_threshold: " + W::num(p.adaptive_threshold, "adaptive_threshold"));
}

}  // namespace

std::string scene_to_yaml(const Scene& scene, const std::string& mesh_stem) {
  Writer w;
  w.line(0, "# Written by strahl " + std::string("(scene_to_yaml); docs/scene-format.md describes every key."));
  camera(w, scene.camera);
  render_settings(w, scene.settings);
  if (!scene.lights().empty()) {
    w.line(0, "lights:");
    for (const Light& l : scene.lights()) light(w, l);
  }
  const TextureFiles tx(scene, mesh_stem);
  int meshes = 0;  // numbered in the order written: the groups' first (save_scene writes their files so)
  if (!scene.groups.empty()) {
    w.line(0, "groups:");
    for (const ObjectGroup& g : scene.groups) {
      w.line(2, Writer::quoted(g.name) + ":");
      for (const auto& o : g.objects) {
        Writer sub;
        object(sub, *o, scene.groups, tx, mesh_stem, meshes);
        w.lines(2, sub);
      }
    }
  }
  w.line(0, "objects:");
  for (const auto& o : scene.objects()) object(w, *o, scene.groups, tx, mesh_stem, meshes);
  return w.text;
}

std::string mesh_to_obj(const MeshData& mesh) {
  using W = Writer;
  Writer w;
  w.line(0, "# Written by strahl (mesh_to_obj)");
  const auto coords = [](const Vec3& v, const char* what) {
    return W::num(v.x, what) + " " + W::num(v.y, what) + " " + W::num(v.z, what);
  };
  for (const Vec3& p : mesh.positions) w.line(0, "v " + coords(p, "mesh vertex"));
  for (const Vec3& n : mesh.normals) w.line(0, "vn " + coords(n, "mesh normal"));
  for (const Texcoord& t : mesh.texcoords)
    w.line(0, "vt " + W::num(t.u, "mesh texture coordinate") + " " + W::num(t.v, "mesh texture coordinate"));
  for (const MeshData::Face& f : mesh.faces) {
    // compile() shades a face smoothly only when all three corners have normals, and keeps its
    // texture coordinates only when all three have them.
    const bool smooth = f.n[0] >= 0 && f.n[1] >= 0 && f.n[2] >= 0;
    const bool mapped = f.t[0] >= 0 && f.t[1] >= 0 && f.t[2] >= 0;
    std::string line = "f";
    for (std::size_t k = 0; k < 3; ++k) {
      line += " " + std::to_string(std::uint64_t(f.v[k]) + 1);
      if (mapped) line += "/" + std::to_string(std::int64_t(f.t[k]) + 1);
      if (smooth) line += (mapped ? "/" : "//") + std::to_string(std::int64_t(f.n[k]) + 1);
    }
    w.line(0, line);
  }
  return w.text;
}

void save_scene(const Scene& scene, const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".yaml" && ext != ".yml")
    throw Error(FileLoc{path.string()}, "unknown scene format '" + ext + "' for writing (use .yaml or .yml)");
  const std::string stem = path.stem().string();
  const std::string text = scene_to_yaml(scene, stem);  // (checks every number before anything is written)
  const auto write = [](const std::filesystem::path& target, const std::string& bytes) {
    OutputFile out(target);
    out.write(bytes.data(), bytes.size());
    out.commit();
  };
  std::vector<std::string> objs;  // every file's text first: a number that cannot be written fails before any file
  const auto add_meshes = [&](const std::vector<std::unique_ptr<SceneObject>>& objects) {
    for (const auto& o : objects)
      if (const auto* m = dynamic_cast<const Mesh*>(o.get()))
        objs.push_back(m->file_materials.empty() ? mesh_to_obj(m->data) : std::string());  // (one names its own file)
  };
  for (const ObjectGroup& g : scene.groups) add_meshes(g.objects);  // in the order scene_to_yaml numbers them
  add_meshes(scene.objects());
  for (std::size_t i = 0; i < objs.size(); ++i)
    if (!objs[i].empty()) write(path.parent_path() / mesh_file(stem, int(i)), objs[i]);
  std::vector<const Image*> pictures;
  picture_numbers(scene, &pictures);
  for (std::uint32_t i = 0; i < pictures.size(); ++i)  // (linear float: the pixels exactly)
    write_image(*pictures[i], path.parent_path() / texture_file(stem, i));
  write(path, text);
}

}  // namespace strahl
