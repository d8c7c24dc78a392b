// POV-Ray scenes in strahl's format (pov_scene.h): the parsed records (pov_reader.h) written as
// the YAML that docs/scene-format.md describes, one line per item so that the reader's errors
// and warnings can be given the .pov location of the item they concern.

#include "strahl/scene/pov/pov_scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>

#include "strahl/scene/csg.h"
#include "strahl/scene/pov/pov_reader.h"
#include "strahl/scene/scene_file.h"
#include "strahl/util/number_syntax.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using pov::Color;
using pov::cross;
using pov::dot;
using pov::length;
using pov::minus;
using pov::Vector;
using pov::yaml_number;
using pov::yaml_vector;

std::string rgb(const Color& c) { return yaml_vector({c[0], c[1], c[2]}); }

class Writer {
 public:
  Writer(pov::Parsed& parsed, const PovOptions& options, const std::string& name)
      : p_(parsed), options_(options), file_{name, 0, 0} {}

  PovTranslation run() {
    t_.warnings = std::move(p_.warnings);
    const pov::Camera& c = p_.camera;
    // POV-Ray's camera is left-handed (its image the mirror image of strahl's right-handed
    // {u, v, w} camera's) where (up × direction)·right > 0, as by default: then the whole scene
    // is mirrored in x, the camera with it, which gives POV-Ray's picture.
    mirror_ = dot(cross(c.up, c.direction), c.right) > 0;
    camera();
    render();
    line("lights:", {});
    if (p_.lights.empty()) t_.yaml.back() = ' ', t_.yaml += "[]\n";
    for (const pov::Light& l : p_.lights) line(light(l), l.loc);
    line("objects:", {});
    if (p_.objects.empty()) t_.yaml.back() = ' ', t_.yaml += "[]\n";
    for (const pov::Object& o : p_.objects) line("  - " + object(o, &p_.default_texture), o.loc);
    t_.meshes = std::move(p_.meshes);
    return std::move(t_);
  }

 private:
  // One line of YAML, from the item at `loc` (none: the file as a whole).
  void line(const std::string& text, const FileLoc& loc) {
    t_.yaml += text + "\n";
    t_.line_locs.push_back(loc.file.empty() ? file_ : loc);
  }

  // A parallel light is directional (along point_at − position); a spotlight (not parallel) a
  // spot light with POV-Ray's radius, falloff and tightness.
  std::string light(const pov::Light& l) const {
    // (POV-Ray draws a light with fade_distance 0 as one without a fade.)
    const bool fades = l.fade_power > 0 && l.fade_distance > 0 && !l.parallel;
    const std::string fade =
        fades ? ", fade_distance: " + yaml_number(l.fade_distance) + ", fade_power: " + yaml_number(l.fade_power) : "";
    const std::string color = ", color: " + rgb(l.color) + fade + "}";
    if (l.parallel) return "  - {type: directional, direction: " + yaml_vector(mirrored(minus(l.point_at, l.position))) + color;
    if (!l.spotlight) return "  - {type: point, position: " + yaml_vector(mirrored(l.position)) + color;
    return "  - {type: spot, position: " + yaml_vector(mirrored(l.position)) + ", point_at: " +
           yaml_vector(mirrored(l.point_at)) + ", angle: " + yaml_number(l.radius) + ", falloff: " +
           yaml_number(l.falloff) + ", tightness: " + yaml_number(l.tightness) + color;
  }

  void camera() {
    const pov::Camera& c = p_.camera;
    // POV-Ray's camera ray: direction + s·right + t·up, s and t in [−1/2, 1/2]; `angle` sets
    // |direction| = |right|/2 / tan(angle/2).
    const double right = length(c.right), up = length(c.up);
    const double d = c.has_angle ? right / 2 / std::tan(c.angle * pov::kPi / 360) : length(c.direction);
    const Vector look_at = c.has_look_at ? c.look_at : Vector{c.location[0] + c.direction[0], c.location[1] + c.direction[1], c.location[2] + c.direction[2]};
    std::string s = "camera: {position: " + yaml_vector(mirrored(c.location)) + ", look_at: " + yaml_vector(mirrored(look_at)) +
                    ", up: " + yaml_vector(mirrored(c.has_look_at ? c.sky : c.up));
    const double aspect = double(options_.width) / options_.height;
    if (c.has_angle && std::fabs(right / up - aspect) <= 1e-12 * aspect) {
      s += ", fov: " + yaml_number(c.angle) + ", fov_axis: horizontal";
    } else {
      s += ", image_plane: {l: " + yaml_number(-right / 2) + ", r: " + yaml_number(right / 2) + ", b: " + yaml_number(-up / 2) + ", t: " + yaml_number(up / 2) +
           ", d: " + yaml_number(d) + "}";
    }
    if (c.aperture > 0 && c.has_focal_point) {
      // POV-Ray's lens offsets are aperture/2 times points of a disc of radius 1/2 (its
      // JitterCameraRay): a thin lens of radius aperture/4, focused at |focal_point − location|.
      s += ", aperture: " + yaml_number(c.aperture / 4) + ", focus_distance: " + yaml_number(length(minus(c.focal_point, c.location)));
    }
    line(s + "}", c.loc);
  }

  void render() {
    int depth = p_.max_trace_level;
    if (depth < 1 || depth > 64) {
      t_.warnings.push_back(file_.str() + ": max_trace_level " + std::to_string(depth) + " is drawn as max_depth " + (depth < 1 ? "1" : "64"));
      depth = depth < 1 ? 1 : 64;
    }
    std::string s = "render: {width: " + std::to_string(options_.width) + ", height: " + std::to_string(options_.height) +
                    ", max_depth: " + std::to_string(depth) + ", ambient_light: " + rgb(p_.ambient_light) +
                    ", background: " + rgb(p_.background);
    if (p_.radiosity) s += ", integrator: path";
    if (p_.camera.aperture > 0 && p_.camera.blur_samples > 0)
      s += ", sampler: stratified, spp: " + std::to_string(p_.camera.blur_samples);
    line(s + "}", {});
  }

  // `moving`: the object's transforms that move its texture (those after the pigment, and the mirror).
  std::string material(const pov::Texture& t, const FileLoc& loc, const std::vector<std::string>& moving) {
    for (const std::string& n : t.notes)
      if (std::find(t_.warnings.begin(), t_.warnings.end(), n) == t_.warnings.end()) t_.warnings.push_back(n);
    const pov::Pigment& p = t.pigment;
    const pov::Finish& f = t.finish;
    const bool phong = f.phong > 0 && f.specular == 0;
    std::string s = "{color: " + rgb(p.color) + ", ambient: " + yaml_number(f.ambient) + ", diffuse: " + yaml_number(f.diffuse) +
                    ", specular: " + yaml_number(phong ? f.phong : f.specular) +
                    ", shininess: " + yaml_number(phong ? 4 * f.phong_size : 1 / f.roughness);
    if (f.reflection != 0) s += ", reflectivity: " + yaml_number(f.reflection);
    if (f.emission[0] != 0 || f.emission[1] != 0 || f.emission[2] != 0)  // POV-Ray: emission × the pigment's colour
      s += ", emission: " + yaml_vector({f.emission[0] * p.color[0], f.emission[1] * p.color[1], f.emission[2] * p.color[2]});
    const double filter = p.color[3], transmit = p.color[4];
    if (filter + transmit != 0) {
      s += ", transparency: " + yaml_number(filter + transmit);
      if (filter > 0) s += ", filter: true";
      if (filter > 0 && transmit > 0)
        warn(loc, "a pigment's filter and transmit together are drawn as filter (strahl tints all transmitted light)");
    }
    if (t.interior.ior != 1) s += ", ior: " + yaml_number(t.interior.ior);
    if (f.fresnel || t.interior.fresnel) s += ", fresnel: true";
    if (p.checker) s += ", checker: {size: " + yaml_number(p.scale) + ", color: " + rgb(p.color2) + "}";
    if (!p.image.empty()) {
      // The pigment's own transforms act first, then the object's that came after it.
      std::vector<std::string> steps = p.steps;
      steps.insert(steps.end(), moving.begin(), moving.end());
      s += ", image: {" + p.image + ", mapping: " + (p.uv ? "uv" : p.mapping) + ", " + p.image_options;
      if (!steps.empty()) s += ", transform: [" + join(steps) + "]";
      s += "}";
    }
    return s + "}";
  }

  static std::string join(const std::vector<std::string>& steps) {
    std::string s;
    for (std::size_t i = 0; i < steps.size(); ++i) s += (i ? ", " : "") + steps[i];
    return s;
  }

  void warn(const FileLoc& loc, const std::string& message) { t_.warnings.push_back(loc.str() + ": " + message); }

  // An object as a YAML flow map. `texture`: the material of the outermost node (CSG operands
  // have none of their own in strahl's format).
  std::string object(const pov::Object& o, const pov::Texture* fallback) {
    const pov::Texture* texture = o.texture.given() ? &o.texture : first_operand_texture(o);
    if (!texture) texture = fallback;
    check_operand_textures(o, true);
    const std::string mirror = mirror_ ? "{scale: [-1, 1, 1]}" : "";
    // What moves an image_map: the object's transforms after its pigment (all of them for the
    // #default texture, which the object has from the start; the outermost node's for an operand's).
    // A uv-mapped one lies on the surface's UVs: nothing moves it.
    const bool uv = texture->pigment.uv && !texture->pigment.image.empty();
    if (uv) check_uvs(o);
    std::vector<std::string> moving(o.steps.begin() + std::ptrdiff_t(texture == &o.texture ? o.texture_steps : 0),
                                    o.steps.end());
    if (!mirror.empty()) moving.push_back(mirror);
    if (uv) moving.clear();
    if (!texture->pigment.image.empty() && !uv) {
      if (texture != &o.texture && texture != fallback)
        warn(o.loc, "a CSG operand's image_map is placed by the outermost node's transforms only");
    }
    std::string s = shape(o, mirror);
    if (o.inverse) s = "{type: inverse, objects: [" + s + "]";
    else s.pop_back();  // its '}'
    return s + ", material: " + material(*texture, o.loc, moving) + "}";
  }

  // A uv-mapped image needs the UVs of a mesh (uv_vectors): strahl has no UV parametrisation of
  // POV-Ray's other shapes.
  void check_uvs(const pov::Object& o) const {
    if (o.mesh < 0) {
      const std::string name = o.type == "disk" ? "disc" : o.type == "implicit" ? "isosurface" : o.type;
      throw Error(o.loc, "uv_mapping on a " + name + ": strahl reads uv-mapped images on meshes with uv_vectors only "
                         "(POV-Ray's own UV mapping of a " + name + " is not read)");
    }
    if (p_.meshes[std::size_t(o.mesh)].texcoords.empty())
      throw Error(o.loc, "uv_mapping on a mesh without uv_vectors (POV-Ray reads the image at <0, 0> all over it)");
  }

  Vector mirrored(const Vector& v) const { return mirror_ ? Vector{0 - v[0], v[1], v[2]} : v; }  // (0 − 0 = +0)

  // `last_step`: a step after the object's own (the mirror), for the outermost node.
  std::string shape(const pov::Object& o, const std::string& last_step = "") {
    std::string s = "{type: " + o.type;
    if (o.mesh >= 0) {
      // Each mesh goes to the reader once: a declared mesh used again is a copy.
      std::size_t i = std::size_t(o.mesh);
      if (i < mesh_used_.size() && mesh_used_[i]) {
        p_.meshes.push_back(p_.meshes[i]);
        i = p_.meshes.size() - 1;
      }
      mesh_used_.resize(p_.meshes.size());
      mesh_used_[i] = true;
      s += ", file: pov-mesh-" + std::to_string(i);
    }
    s += o.keys;
    if (!o.children.empty()) {
      s += ", objects: [";
      for (std::size_t i = 0; i < o.children.size(); ++i) {
        const pov::Object& c = o.children[i];
        s += (i ? ", " : "") + (c.inverse ? "{type: inverse, objects: [" + shape(c) + "]}" : shape(c));
      }
      s += "]";
    }
    std::vector<std::string> steps = o.steps;
    if (!last_step.empty()) steps.push_back(last_step);
    if (!steps.empty()) s += ", transform: [" + join(steps) + "]";
    return s + "}";
  }

  static const pov::Texture* first_operand_texture(const pov::Object& o) {
    for (const pov::Object& c : o.children) {
      if (c.texture.given()) return &c.texture;
      if (const pov::Texture* t = first_operand_texture(c)) return t;
    }
    return nullptr;
  }
  void check_operand_textures(const pov::Object& o, bool outermost) {
    if (!outermost && o.texture.given() && !warned_operands_) {
      warned_operands_ = true;
      warn(o.loc, "CSG operands' own textures are left out: strahl gives a CSG tree one material (the outermost "
                  "node's, else its first operand's)");
    }
    for (const pov::Object& c : o.children) check_operand_textures(c, false);
  }

  pov::Parsed& p_;
  const PovOptions& options_;
  PovTranslation t_;
  bool warned_operands_ = false;
  bool mirror_ = false;
  FileLoc file_;
  std::vector<bool> mesh_used_;
};

// "NAME:LINE:COLUMN: message" of the YAML text → the .pov location of that line's item.
std::string relocate(const std::string& message, const std::string& name, const std::vector<FileLoc>& locs) {
  const std::string prefix = name + ":";
  if (message.rfind(prefix, 0) != 0) return message;
  std::size_t i = prefix.size(), line = 0;
  while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]))) line = line * 10 + std::size_t(message[i++] - '0');
  if (i < message.size() && message[i] == ':') {
    ++i;
    while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]))) ++i;
  }
  if (message.compare(i, 2, ": ") != 0) return message;
  const FileLoc loc = line >= 1 && line <= locs.size() ? locs[line - 1] : FileLoc{};
  return (loc.file.empty() ? name : loc.str()) + message.substr(i);
}

// The locations a scene read from the translation holds (objects and their operands, lights,
// camera, settings: compile() names them in its errors) taken back to the .pov file.
void relocate(SceneObject& o, const std::function<void(FileLoc&)>& back) {
  back(o.loc);
  if (auto* csg = dynamic_cast<Csg*>(&o))
    for (const auto& c : csg->children) relocate(*c, back);
}
void relocate(Scene& scene, const std::function<void(FileLoc&)>& back) {
  for (const auto& o : scene.objects()) relocate(*o, back);
  for (FileLoc& l : scene.light_locs()) back(l);
  back(scene.camera.loc);
  back(scene.settings.loc);
}

}  // namespace

PovTranslation translate_pov(const std::string& text, const std::string& name, const PovOptions& options) {
  pov::Parsed parsed = pov::parse_pov(text, name, options);
  return Writer(parsed, options, name).run();
}

Scene parse_pov_scene(const std::string& text, const std::string& pov_name, const PovOptions& options) {
  PovTranslation t = translate_pov(text, pov_name, options);
  const std::string name = pov_name + " (as YAML)";
  MeshSource meshes = [&](const std::string& file) -> MeshData {
    const std::string prefix = "pov-mesh-";
    const std::size_t i = file.rfind(prefix, 0) == 0 ? std::stoul(file.substr(prefix.size())) : t.meshes.size();
    if (i >= t.meshes.size()) throw Error("no such mesh");
    return std::move(t.meshes[i]);
  };
  try {
    Scene scene = parse_scene(t.yaml, name, fs::path(pov_name).parent_path(), meshes);
    relocate(scene, [&](FileLoc& l) {
      if (l.file == name && l.line >= 1 && std::size_t(l.line) <= t.line_locs.size()) l = t.line_locs[std::size_t(l.line - 1)];
    });
    for (std::string& w : scene.warnings) w = relocate(w, name, t.line_locs);
    scene.warnings.insert(scene.warnings.begin(), t.warnings.begin(), t.warnings.end());
    return scene;
  } catch (const Error& e) {
    const FileLoc loc = e.loc().file == name && e.loc().line >= 1 && std::size_t(e.loc().line) <= t.line_locs.size()
                            ? t.line_locs[std::size_t(e.loc().line - 1)]
                            : FileLoc{};
    if (loc.file.empty()) throw Error(relocate(e.what(), name, t.line_locs));
    const std::string what = e.what(), prefix = e.loc().str() + ": ";
    throw Error(loc, what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what);
  }
}

}  // namespace strahl
