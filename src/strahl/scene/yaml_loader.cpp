// Reads YAML/JSON scene files into a Scene. Strict: unknown keys, wrong types and impossible
// values are errors naming file:line:column of the offending node.

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <map>
#include <sstream>
#include <string_view>
#include <vector>

#include "strahl/scene/instances.h"
#include "strahl/scene/mesh_file.h"
#include "strahl/scene/place_solid.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/solids.h"
#include "strahl/scene/validate.h"
#include "strahl/scene/yaml_csg.h"
#include "strahl/scene/yaml_limits.h"
#include "strahl/scene/yaml_merge.h"
#include "strahl/shading/area_light.h"
#include "strahl/util/cancel.h"
#include "strahl/util/large_pages.h"
#include "strahl/util/number_syntax.h"
#include "strahl/util/system_error.h"

namespace strahl {
namespace fs = std::filesystem;

bool named_ior(const std::string& name, Real& ior) {
  static const std::map<std::string, Real> kIors = {{"vacuum", 1.0},  {"air", 1.0003},    {"water", 1.333},
                                                    {"ice", 1.31},    {"acrylic", 1.491}, {"glass", 1.5},
                                                    {"diamond", 2.419}};
  const auto it = kIors.find(name);
  if (it == kIors.end()) return false;
  ior = it->second;
  return true;
}

namespace {

using Keys = std::initializer_list<std::string_view>;

struct ObjectText {
  int line;          // of its first line in the file, 0-based
  std::string text;  // from there on, the `- ` before it blanked
};

class Reader {
 public:
  Reader(std::string name, fs::path base_dir, MeshSource meshes)
      : name_(std::move(name)), base_dir_(std::move(base_dir)), meshes_(std::move(meshes)) {}

  // `objects`: when not empty, the text of each element of the top-level objects list, read one
  // at a time (the list itself was blanked out of `root`'s text, line numbers kept).
  Scene read(const YAML::Node& root, const std::vector<ObjectText>& objects = {}) {
    Scene scene;
    if (root.IsNull()) fail(root, "the scene file is empty");
    map(root, "scene");
    keys(root, {"camera", "render", "materials", "groups", "lights", "objects"}, "scene");
    if (const YAML::Node n = root["render"]) render(n, scene.settings);
    if (const YAML::Node n = root["camera"]) camera(n, scene.camera);
    if (const YAML::Node n = root["materials"]) {
      map(n, "materials");
      for (const auto& kv : n) {
        const std::string name = scalar(kv.first, "material name");
        if (materials_.count(name)) fail(kv.first, "material '" + name + "' is defined twice");
        materials_[name] = material(kv.second);
      }
    }
    if (const YAML::Node n = root["groups"]) groups(n, scene);
    if (const YAML::Node n = root["lights"]) {
      sequence(n, "lights");
      for (const YAML::Node& l : n) light(l, scene);
    }
    if (!objects.empty()) {
      for (const ObjectText& o : objects) {
        check_cancelled("yaml");
        YAML::Node element;
        try {
          element = YAML::Load(o.text);
        } catch (const YAML::Exception& e) {
          throw Error(FileLoc{name_, o.line + e.mark.line + 1, e.mark.column + 1}, "syntax error: " + e.msg);
        }
        if (may_hold_merge_keys(o.text)) expand_merge_keys(element, name_, o.line);
        line_offset_ = o.line;
        object(element, scene);
        line_offset_ = 0;
      }
    } else if (const YAML::Node n = root["objects"]) {
      sequence(n, "objects");
      for (const YAML::Node& o : n) {
        check_cancelled("yaml");
        object(o, scene);
      }
    }
    if (scene.objects().empty()) fail(root, "the scene has no objects");
    return scene;
  }

 private:
  FileLoc loc(const YAML::Node& n) const {
    const YAML::Mark m = n.Mark();
    return FileLoc{name_, m.line >= 0 ? m.line + 1 + line_offset_ : 0, m.column >= 0 ? m.column + 1 : 0};
  }
  [[noreturn]] void fail(const YAML::Node& n, const std::string& message) const { throw Error(loc(n), message); }

  void map(const YAML::Node& n, const std::string& what) const {
    if (!n.IsMap()) fail(n, what + " must be a map of keys to values");
  }
  void sequence(const YAML::Node& n, const std::string& what) const {
    if (!n.IsSequence()) fail(n, what + " must be a list");
  }
  void keys(const YAML::Node& n, Keys allowed, const std::string& what) const {
    std::vector<std::string> seen;
    for (const auto& kv : n) {
      const std::string key = kv.first.Scalar();
      // yaml-cpp keeps the first of repeated keys; a repeated key is almost always a mistake.
      if (std::find(seen.begin(), seen.end(), key) != seen.end()) fail(kv.first, "repeated key '" + key + "' in " + what);
      seen.push_back(key);
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        std::string list;
        for (std::string_view k : allowed) list += (list.empty() ? "" : ", ") + std::string(k);
        fail(kv.first, "unknown key '" + key + "' in " + what + " (allowed: " + list + ")");
      }
    }
  }
  YAML::Node required(const YAML::Node& n, const char* key, const std::string& what) const {
    const YAML::Node v = n[key];
    if (!v) fail(n, what + " needs '" + key + "'");
    return v;
  }
  std::string scalar(const YAML::Node& n, const std::string& what) const {
    if (!n.IsScalar()) fail(n, what + " must be a single value");
    return n.Scalar();
  }
  // Numbers follow YAML 1.2's core schema (util/number_syntax.h, docs/scene-format.md "Numbers"):
  // a quoted scalar or one tagged !!str is text, not a number, as YAML says.
  void plain(const YAML::Node& n, const std::string& what, const char* kind) const {
    const std::string& tag = n.Tag();
    if (tag == "!" || tag == "tag:yaml.org,2002:str")
      fail(n, what + " must be " + kind + ", not the quoted text \"" + n.Scalar() + "\" (write it without quotes)");
  }
  Real number(const YAML::Node& n, const std::string& what) const {
    if (!n.IsScalar()) fail(n, what + " must be a number");
    plain(n, what, "a number");
    const number::Real r = number::parse_real(n.Scalar());
    if (r.status == number::Real::Status::NotANumber) fail(n, what + " must be a number (got '" + n.Scalar() + "')");
    if (r.status == number::Real::Status::TooLarge)
      fail(n, what + " must be a finite number (" + n.Scalar() + " is beyond the largest double, about 1.8e308)");
    if (!std::isfinite(r.value)) fail(n, what + " must be a finite number");
    return r.value;
  }
  // A whole number in [lo, hi]: decimal (leading zeros too: 010 is 10), 0o octal, 0x hex, or a
  // real of whole value (1e3); never wrapped or clamped.
  std::uint64_t whole(const YAML::Node& n, const std::string& what, std::int64_t lo, std::uint64_t hi) const {
    if (!n.IsScalar()) fail(n, what + " must be a whole number");
    plain(n, what, "a whole number");
    const number::Integer r = number::parse_integer(n.Scalar(), lo, hi);
    switch (r.status) {
      case number::Integer::Status::Ok: return r.unsigned_value;
      case number::Integer::Status::NotANumber: fail(n, what + " must be a whole number (got '" + n.Scalar() + "')");
      case number::Integer::Status::NotWhole: fail(n, what + " must be a whole number (got '" + n.Scalar() + "')");
      case number::Integer::Status::OutOfRange: fail(n, number::range_message(what, lo, hi, n.Scalar()));
    }
    return 0;
  }
  int integer(const YAML::Node& n, const std::string& what, int lo, int hi) const {
    return static_cast<int>(whole(n, what, lo, std::uint64_t(hi)));  // lo ≥ 0 for every setting
  }
  // YAML 1.2 core booleans only: true/True/TRUE, false/False/FALSE (not 1.1's yes, on, y).
  bool boolean(const YAML::Node& n, const std::string& what) const {
    const std::string s = n.IsScalar() ? n.Scalar() : std::string();
    const bool quoted = n.IsScalar() && (n.Tag() == "!" || n.Tag() == "tag:yaml.org,2002:str");
    if (!quoted && (s == "true" || s == "True" || s == "TRUE")) return true;
    if (!quoted && (s == "false" || s == "False" || s == "FALSE")) return false;
    fail(n, what + " must be true or false" + (n.IsScalar() ? " (got '" + s + "')" : std::string()));
  }
  Vec3 vec3(const YAML::Node& n, const std::string& what) const {
    if (!n.IsSequence() || n.size() != 3) fail(n, what + " must be a list of three numbers [x, y, z]");
    return {number(n[0], what), number(n[1], what), number(n[2], what)};
  }
  // A colour: [r, g, b] or one number for grey; components must not be negative.
  Vec3 color(const YAML::Node& n, const std::string& what) const {
    const Vec3 c = n.IsScalar() ? Vec3(number(n, what)) : vec3(n, what);
    validate::non_negative(c, loc(n), what);
    return c;
  }
  Real non_negative(const YAML::Node& n, const std::string& what) const {
    const Real v = number(n, what);
    validate::non_negative(v, loc(n), what);
    return v;
  }
  Real positive(const YAML::Node& n, const std::string& what) const {
    const Real v = number(n, what);
    validate::positive(v, loc(n), what);
    return v;
  }
  Real unit(const YAML::Node& n, const std::string& what) const {
    const Real v = number(n, what);
    validate::in_range(v, 0, 1, loc(n), what);
    return v;
  }
  // An index of refraction by number or by name; errors name the key (`ior`, `medium_ior`).
  Real ior(const YAML::Node& n, const std::string& what) const {
    Real v = 0;
    if (n.IsScalar() && named_ior(n.Scalar(), v)) return v;
    if (n.IsScalar() && number::parse_real(n.Scalar()).status == number::Real::Status::NotANumber && n.Tag() == "?")
      fail(n, "unknown " + what + " '" + n.Scalar() + "' (a number or one of vacuum, air, water, ice, acrylic, glass, diamond)");
    return positive(n, what);
  }

  void render(const YAML::Node& n, RenderSettings& s) const {
    map(n, "render");
    keys(n, {"width", "height", "max_depth", "min_weight", "ray_budget", "supersample", "background", "ambient_light", "medium_ior",
             "accel", "sampler", "spp", "seed", "filter", "filter_radius", "adaptive_min", "adaptive_threshold"},
         "render");
    s.loc = loc(n);
    if (const auto v = n["width"]) s.width = integer(v, "width", 1, 65536);
    if (const auto v = n["height"]) s.height = integer(v, "height", 1, 65536);
    if (const auto v = n["max_depth"]) s.max_depth = integer(v, "max_depth", 1, 64);
    if (const auto v = n["min_weight"]) s.min_weight = unit(v, "min_weight");
    if (const auto v = n["ray_budget"]) s.ray_budget = integer(v, "ray_budget", 0, int(kMaxRayBudget));
    if (const auto v = n["supersample"]) s.supersample = integer(v, "supersample", 1, 64);
    if (const auto v = n["background"]) s.background = color(v, "background");
    if (const auto v = n["ambient_light"]) s.ambient_light = color(v, "ambient_light");
    if (const auto v = n["medium_ior"]) s.medium_ior = ior(v, "medium_ior");
    if (const auto v = n["accel"]) {
      const std::optional<AccelKind> kind = accel_from_name(scalar(v, "accel"));
      if (!kind) fail(v, "unknown accel '" + v.Scalar() + "' (" + accel_names() + ")");
      s.accel = *kind;
    }
    sampling(n, s.sampling);
  }

  void sampling(const YAML::Node& n, SamplingSettings& s) const {
    if (const auto v = n["sampler"]) {
      const std::optional<SamplerKind> kind = sampler_from_name(scalar(v, "sampler"));
      if (!kind) fail(v, "unknown sampler '" + v.Scalar() + "' (" + kSamplerNames + ")");
      s.sampler = *kind;
    }
    if (const auto v = n["spp"]) s.spp = integer(v, "spp", 1, kMaxSpp);
    if (const auto v = n["seed"]) s.seed = whole(v, "seed", 0, std::numeric_limits<std::uint64_t>::max());
    if (const auto v = n["filter"]) {
      const std::optional<FilterKind> kind = filter_from_name(scalar(v, "filter"));
      if (!kind) fail(v, "unknown filter '" + v.Scalar() + "' (" + kFilterNames + ")");
      s.filter.kind = *kind;
    }
    if (const auto v = n["filter_radius"]) {
      s.filter.radius = number(v, "filter_radius");
      if (!(s.filter.radius >= kMinFilterRadius && s.filter.radius <= kMaxFilterRadius))
        fail(v, "filter_radius must lie in [0.5, 4] pixels");
    }
    if (const auto v = n["adaptive_min"]) s.adaptive_min = integer(v, "adaptive_min", 1, kMaxSpp);
    if (const auto v = n["adaptive_threshold"]) s.adaptive_threshold = positive(v, "adaptive_threshold");
  }

  void camera(const YAML::Node& n, CameraDescription& c) const {
    map(n, "camera");
    keys(n, {"position", "look_at", "up", "fov", "fov_axis", "image_plane", "aperture", "focus_distance", "focus_point",
             "shutter"},
         "camera");
    c.loc = loc(n);
    if (const auto v = n["position"]) c.position = vec3(v, "camera position");
    if (const auto v = n["look_at"]) c.look_at = vec3(v, "camera look_at");
    if (const auto v = n["up"]) {
      c.up = vec3(v, "camera up");
      validate::non_zero(c.up, loc(v), "camera up");
    }
    if (const auto v = n["fov"]) {
      c.fov_degrees = number(v, "fov");
      if (!(c.fov_degrees > 0 && c.fov_degrees < 180)) fail(v, "fov must lie in (0, 180) degrees");
    }
    if (const auto v = n["fov_axis"]) {
      const std::string axis = scalar(v, "fov_axis");
      if (axis == "horizontal") c.fov_axis = CameraDescription::FovAxis::Horizontal;
      else if (axis == "vertical") c.fov_axis = CameraDescription::FovAxis::Vertical;
      else fail(v, "fov_axis must be 'horizontal' or 'vertical'");
    }
    if (const auto p = n["image_plane"]) {
      if (n["fov"] || n["fov_axis"]) fail(p, "give either fov or image_plane, not both");
      map(p, "image_plane");
      keys(p, {"l", "r", "b", "t", "d"}, "image_plane");
      c.explicit_image_plane = true;
      c.l = number(required(p, "l", "image_plane"), "l");
      c.r = number(required(p, "r", "image_plane"), "r");
      c.b = number(required(p, "b", "image_plane"), "b");
      c.t = number(required(p, "t", "image_plane"), "t");
      c.d = positive(required(p, "d", "image_plane"), "d");
      if (!(c.l < c.r)) fail(p, "image_plane needs l < r");
      if (!(c.b < c.t)) fail(p, "image_plane needs b < t");
    }
    if (const auto v = n["aperture"]) c.aperture = non_negative(v, "aperture");
    if (const auto v = n["focus_distance"]) c.focus_distance = positive(v, "focus_distance");
    if (const auto v = n["focus_point"]) {
      if (n["focus_distance"]) fail(v, "give either focus_distance or focus_point, not both");
      c.focus_point = vec3(v, "focus_point");
      c.has_focus_point = true;
    }
    if (const auto v = n["shutter"]) {
      if (!v.IsSequence() || v.size() != 2) fail(v, "shutter must be a list of two times [open, close]");
      c.shutter_open = number(v[0], "shutter open");
      c.shutter_close = number(v[1], "shutter close");
      if (c.shutter_close < c.shutter_open) fail(v, "shutter close must not come before shutter open");
    }
    // Directions without squaring (validate::direction): tiny or huge values are no reason to
    // call the camera's up parallel; compile() checks the scale limits at this same node.
    const Vec3 view = c.look_at - c.position;
    if (max_abs_component(view) == 0) fail(n, "camera position and look_at coincide");
    if (length_squared(cross(validate::direction(view), validate::direction(c.up))) < 1e-12)
      fail(n, "camera up is parallel to the viewing direction");
    if (c.has_focus_point && !(dot(c.focus_point - c.position, view) > 0))
      fail(n["focus_point"], "focus_point must lie in front of the camera");
  }

  Material material(const YAML::Node& n) const {
    map(n, "material");
    keys(n, {"color", "ambient", "diffuse", "specular", "shininess", "reflectivity", "transparency", "ior", "fresnel",
             "filter", "checker", "roughness"},
         "material");
    Material m;
    if (const auto v = n["color"]) m.color = color(v, "color");
    if (const auto v = n["ambient"]) m.ambient = non_negative(v, "ambient");
    if (const auto v = n["diffuse"]) m.diffuse = non_negative(v, "diffuse");
    if (const auto v = n["specular"]) m.specular = color(v, "specular");
    if (const auto v = n["shininess"]) m.shininess = non_negative(v, "shininess");
    if (const auto v = n["reflectivity"]) m.reflectivity = unit(v, "reflectivity");
    if (const auto v = n["transparency"]) m.transparency = unit(v, "transparency");
    if (const auto v = n["ior"]) m.ior = ior(v, "ior");
    if (const auto v = n["fresnel"]) m.fresnel = boolean(v, "fresnel");
    if (const auto v = n["filter"]) m.filter = boolean(v, "filter");
    if (const auto v = n["roughness"]) m.roughness = unit(v, "roughness");
    if (const auto c = n["checker"]) {
      map(c, "checker");
      keys(c, {"size", "color"}, "checker");
      m.checker_size = positive(required(c, "size", "checker"), "checker size");
      if (const auto v = c["color"]) m.checker_color = color(v, "checker color");
    }
    return m;
  }

  // `material: name` refers to the materials section; a map defines one in place.
  Material object_material(const YAML::Node& object) const {
    const YAML::Node n = object["material"];
    if (!n) return Material{};
    if (n.IsScalar()) {
      const auto it = materials_.find(n.Scalar());
      if (it == materials_.end()) fail(n, "unknown material '" + n.Scalar() + "'");
      return it->second;
    }
    return material(n);
  }

  void light(const YAML::Node& n, Scene& scene) const {
    map(n, "light");
    const std::string type = scalar(required(n, "type", "light"), "light type");
    const Vec3 c = n["color"] ? color(n["color"], "light color") : Vec3(1);
    const Real intensity = n["intensity"] ? non_negative(n["intensity"], "intensity") : Real(1);
    if (type == "point") {
      keys(n, {"type", "position", "color", "intensity"}, "point light");
      scene.add(point_light(vec3(required(n, "position", "point light"), "light position"), c, intensity), loc(n));
    } else if (type == "directional") {
      keys(n, {"type", "direction", "color", "intensity"}, "directional light");
      const YAML::Node d = required(n, "direction", "directional light");
      const Vec3 dir = vec3(d, "light direction");
      validate::non_zero(dir, loc(d), "light direction");
      scene.add(directional_light(dir, c, intensity), loc(n));
    } else if (type == "rect" || type == "disk" || type == "sphere") {
      area_light(n, type, c, scene);
    } else {
      fail(n["type"], "unknown light type '" + type + "' (point, directional, rect, disk or sphere)");
    }
  }

  // Area lights: radiance L = color × intensity, or from `power` Φ (one-sided: Φ = π·L·area).
  void area_light(const YAML::Node& n, const std::string& type, const Vec3& c, Scene& scene) const {
    const std::string what = type + " light";
    if (type == "rect") keys(n, {"type", "corner", "edge_u", "edge_v", "color", "intensity", "power", "samples"}, what);
    if (type == "disk") keys(n, {"type", "center", "normal", "radius", "color", "intensity", "power", "samples"}, what);
    if (type == "sphere") keys(n, {"type", "center", "radius", "color", "intensity", "power", "samples"}, what);
    if (n["power"] && n["intensity"]) fail(n["power"], "give either intensity or power, not both");
    const int samples = n["samples"] ? integer(n["samples"], "light samples", 1, 64) : 4;
    Light l;
    if (type == "rect") {
      const YAML::Node eu = required(n, "edge_u", what), ev = required(n, "edge_v", what);
      const Vec3 u = vec3(eu, "edge_u"), v = vec3(ev, "edge_v");
      validate::non_zero(u, loc(eu), "edge_u");
      validate::non_zero(v, loc(ev), "edge_v");
      if (std::fabs(dot(validate::direction(u), validate::direction(v))) > 1e-6) fail(ev, "rect light edges must be perpendicular");
      l = rect_light(vec3(required(n, "corner", what), "light corner"), u, v, Vec3(1), samples);
    } else if (type == "disk") {
      const YAML::Node nn = required(n, "normal", what);
      const Vec3 normal = vec3(nn, "light normal");
      validate::non_zero(normal, loc(nn), "light normal");
      l = disk_light(vec3(required(n, "center", what), "light center"), normal,  // compile() normalises it
                     positive(required(n, "radius", what), "light radius"), Vec3(1), samples);
    } else {
      l = sphere_light(vec3(required(n, "center", what), "light center"),
                       positive(required(n, "radius", what), "light radius"), Vec3(1), samples);
    }
    if (const auto p = n["power"]) {
      const Real power = non_negative(p, "power");
      if (type == "rect") l.normal = normalize(cross(l.edge_u, l.edge_v));
      l.radiance = c * radiance_from_power(l, power);
    } else {
      l.radiance = c * (n["intensity"] ? non_negative(n["intensity"], "intensity") : Real(1));
    }
    scene.add(l, loc(n));
  }

  // `motion: {velocity: [x, y, z]}` or `motion: {from: {…}, to: {…}}`, each keyframe a transform
  // as an object's placement is (scale/rotate/translate, a matrix or a transform list).
  Transform transform(const YAML::Node& n, const std::string& what) const {
    map(n, what);
    keys(n, {"scale", "rotate", "translate", "matrix", "transform"}, what);
    return placement(n, "motion ");
  }
  // `spin: {axis: [x, y, z], angle: degrees, center: [x, y, z]}` (center optional) beside either,
  // or alone.
  Motion motion(const YAML::Node& n) const {
    map(n, "motion");
    keys(n, {"velocity", "from", "to", "spin"}, "motion");
    const Spin s = n["spin"] ? spin(n["spin"]) : Spin{};
    if (const auto v = n["velocity"]) {
      if (n["from"] || n["to"]) fail(v, "give either velocity or from/to keyframes, not both");
      return Motion::linear(vec3(v, "velocity")).with_spin(s);
    }
    if (!n["from"] && !n["to"]) {
      if (n["spin"]) return Motion::spinning(s);
      fail(n, "motion needs 'velocity', 'from'/'to' keyframes or a 'spin'");
    }
    const Transform from = n["from"] ? transform(n["from"], "motion from") : Transform{};
    const Transform to = n["to"] ? transform(n["to"], "motion to") : Transform{};
    return Motion::keyframes(from, to).with_spin(s);
  }
  Spin spin(const YAML::Node& n) const {
    map(n, "motion spin");
    keys(n, {"axis", "angle", "center"}, "motion spin");
    Spin s;
    const YAML::Node axis = required(n, "axis", "motion spin");
    s.axis = vec3(axis, "spin axis");
    if (s.axis == Vec3(0)) fail(axis, "spin axis must not be zero");
    s.angle = number(required(n, "angle", "motion spin"), "spin angle");
    if (const auto c = n["center"]) s.center = vec3(c, "spin center");
    return s;
  }

  // `groups: {name: [objects…], …}` (docs/scene-format.md, "Instances"), read before the objects
  // that place them. An object of a group is read as at the top level.
  void groups(const YAML::Node& n, Scene& scene) {
    map(n, "groups");
    for (const auto& kv : n) {
      const std::string name = scalar(kv.first, "group name");
      if (group_index_.count(name)) fail(kv.first, "group '" + name + "' is defined twice");
      if (!kv.second.IsSequence()) fail(kv.second, "group '" + name + "' must be a list of objects");
      ObjectGroup g;
      g.name = name;
      g.loc = loc(kv.first);
      reading_group_ = &name;
      for (const YAML::Node& o : kv.second) {
        Scene objects;
        object(o, objects);
        g.objects.push_back(objects.take_last());
      }
      reading_group_ = nullptr;
      if (g.objects.empty()) fail(kv.second, "group '" + name + "' has no objects");
      group_index_[name] = static_cast<std::uint32_t>(scene.groups.size());
      scene.groups.push_back(std::move(g));
    }
  }

  // `type: instance, of: name` with its own transform.
  SceneObject* instance(const YAML::Node& n, Scene& scene) const {
    keys(n, {"type", "of", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "instance");
    const YAML::Node of = required(n, "of", "instance");
    const std::string name = scalar(of, "instance of");
    // A group places the groups defined above it (nested instances), never itself.
    if (reading_group_ && name == *reading_group_) fail(of, "group '" + name + "' places an instance of itself (a cycle)");
    const auto it = group_index_.find(name);
    if (it == group_index_.end()) {
      std::string known;
      for (const auto& [k, v] : group_index_) known += (known.empty() ? "" : ", ") + k;
      if (reading_group_)
        fail(of, "unknown group '" + name + "': group '" + *reading_group_ + "' can place the groups defined above it" +
                     (known.empty() ? std::string(" (none is)") : " (" + known + ")"));
      fail(of, "unknown group '" + name + "'" + (known.empty() ? std::string(" (the scene defines no groups)") : " (groups: " + known + ")"));
    }
    return &scene.add(Instance(it->second));
  }

  void object(const YAML::Node& n, Scene& scene) const {
    map(n, "object");
    const std::string type = scalar(required(n, "type", "object"), "object type");
    SceneObject* added = nullptr;
    if (type == "instance") {
      added = instance(n, scene);
    } else if (type == "sphere") {
      keys(n, {"type", "center", "radius", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "sphere");
      const Vec3 center = vec3(required(n, "center", "sphere"), "sphere center");
      const Real radius = positive(required(n, "radius", "sphere"), "sphere radius");
      added = &scene.add(Sphere(center, radius, object_material(n)));
    } else if (type == "plane") {
      keys(n, {"type", "normal", "distance", "material", "scale", "rotate", "translate", "matrix", "transform"}, "plane");
      const YAML::Node nn = required(n, "normal", "plane");
      Vec3 normal = vec3(nn, "plane normal");
      validate::non_zero(normal, loc(nn), "plane normal");
      Real distance = n["distance"] ? number(n["distance"], "plane distance") : Real(0);
      if (const Transform t = placement(n); !t.identity()) place_plane(t, normal, distance, loc(n));
      added = &scene.add(Plane(normal, distance, object_material(n)));
    } else if (type == "triangle") {
      keys(n, {"type", "vertices", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "triangle");
      const YAML::Node v = required(n, "vertices", "triangle");
      if (!v.IsSequence() || v.size() != 3) fail(v, "triangle vertices must be a list of three points");
      Vec3 a = vec3(v[0], "vertex"), b = vec3(v[1], "vertex"), c = vec3(v[2], "vertex");
      if (const Transform t = placement(n); !t.identity()) place_triangle(t, a, b, c, loc(n));
      if (!(length_squared(cross(b - a, c - a)) > 0)) fail(v, "degenerate triangle (its vertices are collinear)");
      added = &scene.add(Triangle(a, b, c, object_material(n)));
    } else if (type == "mesh") {
      keys(n, {"type", "file", "material", "scale", "rotate", "translate", "matrix", "transform", "motion"}, "mesh");
      const YAML::Node f = required(n, "file", "mesh");
      const std::string file = scalar(f, "mesh file");
      const Transform t = placement(n, "mesh ");
      const Material m = object_material(n);
      MeshData data;
      try {
        data = meshes_ ? meshes_(file) : load_mesh(base_dir_ / file);
      } catch (const Error& e) {
        fail(f, std::string("mesh: ") + e.what());
      }
      added = &scene.add(Mesh(std::move(data), m, t));
    } else if (SceneObject* solid = this->solid(type, n, scene)) {
      added = solid;
    } else if (is_csg_type(type)) {
      added = &scene.add(csg(n, type));
    } else {
      fail(n["type"], "unknown object type '" + type +
                          "' (sphere, plane, triangle, mesh, box, cylinder, cone, disk, torus, quadric, implicit, "
                          "union, intersection, difference, merge, inverse or instance)");
    }
    added->loc = loc(n);
    if (type != "mesh" && type != "plane" && type != "triangle") added->placement = placement(n);
    if (const auto m = n["motion"]) added->motion = motion(m);
  }

  // Where an object's own coordinates go (docs/scene-format.md, "Transforms"): the fixed-order
  // keys `scale`, `rotate` ([x, y, z] degrees or {axis, angle}) and `translate`, or a `matrix`,
  // or a `transform` list applied in the order written. `what` prefixes the zero-scale message.
  Transform placement(const YAML::Node& n, const std::string& what = "") const {
    if (const YAML::Node list = n["transform"]) {
      for (const char* k : {"scale", "rotate", "translate", "matrix"})
        if (n[k]) fail(n[k], std::string("give either a transform list or '") + k + "', not both (put it in the list)");
      sequence(list, "transform");
      Mat3 m;
      Vec3 t(0);
      for (const YAML::Node& step : list) {
        if (!step.IsMap() || step.size() != 1)
          fail(step, "each step of a transform list must be a map of one key: scale, rotate, translate or matrix");
        const std::string key = step.begin()->first.Scalar();
        const YAML::Node v = step.begin()->second;
        Mat3 sm;
        Vec3 st(0);
        if (key == "scale") sm = Mat3::scale(scale(v, what));
        else if (key == "rotate") sm = rotation(v);
        else if (key == "translate") st = vec3(v, "translate");
        else if (key == "matrix") affine_matrix(v, sm, st);
        else fail(step.begin()->first, "unknown transform step '" + key + "' (scale, rotate, translate or matrix)");
        m = sm * m;
        t = sm * t + st;
      }
      check_determinant(list, m.determinant(), "the transform");
      return Transform::affine(m, t);
    }
    if (const YAML::Node v = n["matrix"]) {
      for (const char* k : {"scale", "rotate", "translate"})
        if (n[k]) fail(n[k], std::string("give either 'matrix' or '") + k + "', not both (or write a transform list)");
      Mat3 m;
      Vec3 t(0);
      affine_matrix(v, m, t);
      return Transform::affine(m, t);
    }
    Transform t;
    if (const auto v = n["scale"]) t.scale = scale(v, what);
    if (const auto v = n["translate"]) t.translate = vec3(v, "translate");
    if (const auto v = n["rotate"]) {
      if (!v.IsMap()) {
        t.rotate_degrees = vec3(v, "rotate");
      } else {  // about an axis: still scale, rotate, translate
        const Mat3 m = rotation(v) * Mat3::scale(t.scale);
        return Transform::affine(m, t.translate);
      }
    }
    return t;
  }
  Vec3 scale(const YAML::Node& v, const std::string& what) const {
    const Vec3 s = v.IsScalar() ? Vec3(number(v, "scale")) : vec3(v, "scale");
    if (s.x == 0 || s.y == 0 || s.z == 0) fail(v, what + "scale must not be zero");
    return s;
  }
  // [x, y, z] (degrees about x, then y, then z) or {axis: [x, y, z], angle: degrees}.
  Mat3 rotation(const YAML::Node& v) const {
    if (!v.IsMap()) {
      const Vec3 r = vec3(v, "rotate");
      return Mat3::rotation(2, r.z) * Mat3::rotation(1, r.y) * Mat3::rotation(0, r.x);
    }
    keys(v, {"axis", "angle"}, "rotate");
    const YAML::Node a = required(v, "axis", "rotate");
    const Vec3 axis = vec3(a, "rotate axis");
    if (axis == Vec3(0)) fail(a, "rotate axis must not be the zero vector");
    return Mat3::rotation(axis / max_abs_component(axis), number(required(v, "angle", "rotate"), "rotate angle"));
  }
  // An affine matrix: three rows of four numbers [m, m, m, t] (or of three: no translation), or
  // four rows whose last is [0, 0, 0, 1]. Not singular.
  void affine_matrix(const YAML::Node& v, Mat3& m, Vec3& t) const {
    const char* shape = "matrix must be a list of 3 or 4 rows of 4 numbers (3 rows of 3: no translation)";
    if (!v.IsSequence() || (v.size() != 3 && v.size() != 4)) fail(v, shape);
    const std::size_t columns = v[0].IsSequence() ? v[0].size() : 0;
    if ((columns != 3 && columns != 4) || (v.size() == 4 && columns != 4)) fail(v, shape);
    Real e[4][4] = {};
    for (std::size_t r = 0; r < v.size(); ++r) {
      if (!v[r].IsSequence() || v[r].size() != columns) fail(v[r], shape);
      for (std::size_t c = 0; c < columns; ++c) e[r][c] = number(v[r][c], "matrix element");
    }
    if (v.size() == 4 && !(e[3][0] == 0 && e[3][1] == 0 && e[3][2] == 0 && e[3][3] == 1))
      fail(v[3], "a 4x4 matrix's last row must be [0, 0, 0, 1] (an affine map; projective ones are not supported)");
    for (int r = 0; r < 3; ++r) m.row[r] = {e[r][0], e[r][1], e[r][2]};
    t = {e[0][3], e[1][3], e[2][3]};
    check_determinant(v, m.determinant(), "matrix");
  }
  void check_determinant(const YAML::Node& v, Real det, const std::string& what) const {
    if (!std::isfinite(det)) fail(v, what + "'s determinant is not finite (its entries are too large)");
    if (det == 0) fail(v, what + " is singular (its determinant is 0): it flattens the object");
  }

  // A CSG node (scene/yaml_csg.cpp); its solid operands are read here as objects of their own.
  Csg csg(const YAML::Node& n, const std::string& type) const {
    CsgReader r;
    r.loc = [this](const YAML::Node& x) { return loc(x); };
    r.keys = [this](const YAML::Node& x, Keys allowed, const std::string& what) { keys(x, allowed, what); };
    r.material = [this](const YAML::Node& x) { return object_material(x); };
    r.placement = [this](const YAML::Node& x) { return placement(x); };
    r.solid = [this](const YAML::Node& x) {
      Scene operand;
      object(x, operand);
      return operand.take_last();
    };
    return read_csg(n, type, r);
  }

  // [[x, y, z], [x, y, z]]: two opposite corners.
  void corners(const YAML::Node& n, const std::string& what, Vec3& a, Vec3& b) const {
    if (!n.IsSequence() || n.size() != 2) fail(n, what + " must be a list of two corners [[x, y, z], [x, y, z]]");
    a = vec3(n[0], what + " corner");
    b = vec3(n[1], what + " corner");
    const Vec3 lo = min(a, b), hi = max(a, b);
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) fail(n, what + " is flat: its corners must differ in x, y and z");
  }
  // {type: box, corners: [...]} (and, where allowed, {type: sphere, center, radius}).
  void bound(const YAML::Node& n, const std::string& what, bool sphere_allowed, ImplicitSurface* s, ClipBox* clip) const {
    map(n, what);
    const std::string type = scalar(required(n, "type", what), what + " type");
    if (type == "box") {
      keys(n, {"type", "corners"}, what);
      Vec3 a, b;
      corners(required(n, "corners", what), what + " box", a, b);
      if (s) { s->bound = kernel::ImplicitBound::Box; s->box_a = a; s->box_b = b; }
      if (clip) *clip = {a, b};
    } else if (type == "sphere" && sphere_allowed) {
      keys(n, {"type", "center", "radius"}, what);
      s->bound = kernel::ImplicitBound::Sphere;
      s->center = vec3(required(n, "center", what), what + " center");
      s->radius = positive(required(n, "radius", what), what + " radius");
    } else {
      fail(n["type"], "unknown " + what + " type '" + type + (sphere_allowed ? "' (box or sphere)" : "' (box)"));
    }
  }

  // The solids (scene/solids.h); nullptr for another type.
  SceneObject* solid(const std::string& type, const YAML::Node& n, Scene& scene) const {
    if (type == "box") {
      keys(n, {"type", "corners", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "box");
      Vec3 a, b;
      corners(required(n, "corners", "box"), "box", a, b);
      return &scene.add(Box(a, b, object_material(n)));
    }
    if (type == "cylinder") {
      keys(n, {"type", "base", "cap", "radius", "open", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "cylinder");
      const Vec3 base = vec3(required(n, "base", "cylinder"), "cylinder base");
      const Vec3 cap = vec3(required(n, "cap", "cylinder"), "cylinder cap");
      if (base == cap) fail(n["cap"], "degenerate cylinder: its base and cap are the same point");
      const Real radius = positive(required(n, "radius", "cylinder"), "cylinder radius");
      const bool open = n["open"] ? boolean(n["open"], "open") : false;
      return &scene.add(Cone::cylinder(base, cap, radius, object_material(n), open));
    }
    if (type == "cone") {
      keys(n, {"type", "base", "base_radius", "cap", "cap_radius", "open", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "cone");
      const Vec3 base = vec3(required(n, "base", "cone"), "cone base");
      const Vec3 cap = vec3(required(n, "cap", "cone"), "cone cap");
      if (base == cap) fail(n["cap"], "degenerate cone: its base and cap are the same point");
      const Real r0 = non_negative(required(n, "base_radius", "cone"), "cone base_radius");
      const Real r1 = non_negative(required(n, "cap_radius", "cone"), "cone cap_radius");
      if (!(r0 > 0 || r1 > 0)) fail(n["cap_radius"], "cone radii are both 0 (one must be positive)");
      const bool open = n["open"] ? boolean(n["open"], "open") : false;
      return &scene.add(Cone(base, r0, cap, r1, object_material(n), open));
    }
    if (type == "disk") {
      keys(n, {"type", "center", "normal", "radius", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "disk");
      const Vec3 center = vec3(required(n, "center", "disk"), "disk center");
      const YAML::Node nn = required(n, "normal", "disk");
      const Vec3 normal = vec3(nn, "disk normal");
      validate::non_zero(normal, loc(nn), "disk normal");
      const Real radius = positive(required(n, "radius", "disk"), "disk radius");
      return &scene.add(Disk(center, normal, radius, object_material(n)));
    }
    if (type == "torus") {
      keys(n, {"type", "center", "axis", "major_radius", "minor_radius", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "torus");
      const Vec3 center = n["center"] ? vec3(n["center"], "torus center") : Vec3(0);
      Vec3 axis(0, 1, 0);
      if (const auto v = n["axis"]) {
        axis = vec3(v, "torus axis");
        validate::non_zero(axis, loc(v), "torus axis");
      }
      const Real major = positive(required(n, "major_radius", "torus"), "torus major_radius");
      const YAML::Node mn = required(n, "minor_radius", "torus");
      const Real minor = positive(mn, "torus minor_radius");
      if (!(minor < major)) fail(mn, "torus minor_radius must be smaller than its major_radius");
      return &scene.add(Torus(center, major, minor, object_material(n), axis));
    }
    if (type == "quadric") {
      keys(n, {"type", "coefficients", "clipped_by", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "quadric");
      const YAML::Node c = required(n, "coefficients", "quadric");
      if (!c.IsSequence() || c.size() != 10)
        fail(c, "quadric coefficients must be a list of ten numbers [A, B, C, D, E, F, G, H, I, J]");
      std::array<Real, 10> k{};
      bool surface = false;
      for (std::size_t i = 0; i < 10; ++i) {
        k[i] = number(c[i], "quadric coefficient");
        surface = surface || (i < 9 && k[i] != 0);
      }
      if (!surface) fail(c, "quadric describes no surface: its coefficients A to I are all 0");
      std::optional<ClipBox> clip;
      if (const auto v = n["clipped_by"]) {
        ClipBox b;
        bound(v, "clipped_by", false, nullptr, &b);
        clip = b;
      }
      return &scene.add(Quadric(k, object_material(n), clip));
    }
    if (type == "implicit") return implicit(n, scene);
    return nullptr;
  }

  SceneObject* implicit(const YAML::Node& n, Scene& scene) const {
    keys(n, {"type", "expression", "parameters", "contained_by", "max_gradient", "accuracy", "method", "step",
             "material", "motion", "scale", "rotate", "translate", "matrix", "transform"},
         "implicit");
    const YAML::Node e = required(n, "expression", "implicit");
    ImplicitSurface s(scalar(e, "implicit expression"), object_material(n));
    if (const auto p = n["parameters"]) {
      map(p, "parameters");
      for (const auto& kv : p) {
        const std::string name = scalar(kv.first, "parameter name");
        if (!valid_parameter_name(name))
          fail(kv.first, "'" + name + "' cannot be a parameter (a name of letters, digits and _, not x, y, z, pi "
                         "or a function)");
        s.parameters[name] = number(kv.second, "parameter " + name);
      }
    }
    // The expression is compiled here too, so that an error points at its column in the file:
    // the text starts one column later when it is quoted.
    try {
      const kernel::Expression f = compile_expression(s.expression, s.parameters);
      if (!uses_coordinates(f)) fail(e, "implicit expression does not use x, y or z: it describes no surface");
    } catch (const ExpressionError& err) {
      FileLoc at = loc(e);
      if (at.column > 0 && e.Tag() != "!") at.column += err.column() - 1;  // a plain scalar, on its own line
      else if (at.column > 0) at.column += err.column();
      throw Error(at, "implicit expression: " + err.message());
    }
    bound(required(n, "contained_by", "implicit"), "contained_by", true, &s, nullptr);
    if (const auto v = n["max_gradient"]) s.max_gradient = positive(v, "max_gradient");
    if (const auto v = n["accuracy"]) s.accuracy = positive(v, "accuracy");
    if (const auto v = n["method"]) {
      const std::string m = scalar(v, "method");
      if (m == "lipschitz") s.method = kernel::RootMethod::Lipschitz;
      else if (m == "distance") s.method = kernel::RootMethod::SphereTrace;
      else if (m == "march") s.method = kernel::RootMethod::March;
      else fail(v, "unknown method '" + m + "' (lipschitz, distance or march)");
    }
    if (const auto v = n["step"]) {
      if (s.method != kernel::RootMethod::March) fail(v, "step is for method: march");
      s.step = positive(v, "step");
    }
    return &scene.add(std::move(s));
  }

  std::string name_;
  fs::path base_dir_;
  MeshSource meshes_;  // empty: mesh files are read from base_dir_
  std::map<std::string, Material> materials_;
  int line_offset_ = 0;  // of the object being read from its own text
  std::map<std::string, std::uint32_t> group_index_;  // into Scene::groups
  const std::string* reading_group_ = nullptr;        // the group whose objects are being read
};

// The scene's text with the top-level objects list cut out (its lines left empty, so line numbers
// stay), and the text of each of its elements: the lines from its start to the next one's, with
// the `- ` in front of it blanked (columns stay). Empty when the outline does not allow it.
struct SplitText {
  std::string rest;
  std::vector<ObjectText> objects;
};
SplitText split_objects(const std::string& text, const YamlOutline& outline) {
  SplitText out;
  if (!outline.objects_by_element) return out;
  std::vector<std::size_t> starts{0};  // of each line
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') starts.push_back(i + 1);
  const auto line_start = [&](int line) { return line < int(starts.size()) ? starts[std::size_t(line)] : text.size(); };
  const int first = outline.elements.front().line;
  const int end = outline.objects_end_line >= 0 ? outline.objects_end_line : int(starts.size());
  std::vector<ObjectText> objects;
  objects.reserve(outline.elements.size());
  for (std::size_t k = 0; k < outline.elements.size(); ++k) {
    const YamlOutline::Element& e = outline.elements[k];
    const int next = k + 1 < outline.elements.size() ? outline.elements[k + 1].line : end;
    if (next <= e.line) return out;  // two elements on one line: read the whole tree
    const std::size_t from = line_start(e.line), to = line_start(next);
    std::string element = text.substr(from, to - from);
    // Only blanks and the element's dash may stand before it on its first line.
    const std::size_t prefix = std::size_t(e.column);
    if (prefix > element.size() || element.substr(0, prefix).find('-') == std::string::npos) return out;
    for (std::size_t i = 0; i < prefix; ++i) {
      if (element[i] != ' ' && element[i] != '\t' && element[i] != '-') return out;
      element[i] = ' ';
    }
    objects.push_back({e.line, std::move(element)});
  }
  out.rest.reserve(text.size() - (line_start(end) - line_start(first)) + std::size_t(end - first));
  out.rest.append(text, 0, line_start(first));
  out.rest.append(std::size_t(std::max(0, std::min(end, int(starts.size())) - first)), '\n');
  out.rest.append(text, line_start(end), std::string::npos);
  out.objects = std::move(objects);
  return out;
}

}  // namespace

namespace {
// Where a second YAML document begins: a `---` line (or a `...` end marker followed by more)
// after the first document's content; line 0 when there is none. Comments and blank lines are
// no content, and a `---` before any content only opens the first document.
FileLoc second_document(const std::string& text, const std::string& name) {
  bool content = false, ended = false;
  int line = 0;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view l(text.data() + start, end - start);
    ++line;
    start = end + 1;
    const auto marker = [&](std::string_view m) {
      return l.substr(0, 3) == m && (l.size() == 3 || l[3] == ' ' || l[3] == '\t' || l[3] == '\r');
    };
    if (marker("---")) {
      if (content || ended) return FileLoc{name, line, 1};
      continue;
    }
    if (marker("...")) {
      ended = content;
      continue;
    }
    const std::size_t first = l.find_first_not_of(" \t\r");
    if (first == std::string_view::npos || l[first] == '#') continue;
    if (ended) return FileLoc{name, line, 1};
    if (l[0] != '%') content = true;  // (a %YAML directive precedes a document's ---)
  }
  return FileLoc{name, 0, 0};
}
}  // namespace

Scene parse_scene(const std::string& text, const std::string& name, const fs::path& base_dir, const MeshSource& meshes) {
  // yaml-cpp reads a NUL byte as the end of the text: a binary or UTF-16 file would be half read.
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
    const std::size_t line_start = text.rfind('\n', nul);
    const int line = 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(nul), '\n'));
    const int column = int(nul - (line_start == std::string::npos ? 0 : line_start + 1)) + 1;
    throw Error(FileLoc{name, line, column}, "not a text file (a NUL byte; scene files are UTF-8 text)");
  }
  // Before the tree is built: an input too large for the format is refused at constant memory.
  // Then the objects are read one at a time where the text allows it, so that memory holds one
  // object's tree, not the whole file's (docs/scene-format.md, "Size limits").
  SplitText split = split_objects(text, check_yaml_limits(text, name));
  YAML::Node root;
  try {
    root = YAML::Load(split.objects.empty() ? text : split.rest);
  } catch (const YAML::Exception& e) {
    throw Error(FileLoc{name, e.mark.line + 1, e.mark.column + 1}, "syntax error: " + e.msg);
  }
  if (may_hold_merge_keys(split.objects.empty() ? text : split.rest)) expand_merge_keys(root, name);
  split.rest = std::string();
  Scene scene = Reader(name, base_dir, meshes).read(root, split.objects);
  // A scene is one document; what follows a second `---` would be silently dropped.
  if (const FileLoc second = second_document(text, name); second.line > 0)
    scene.warnings.push_back(second.str() +
                             ": a second YAML document starts here (after ---); only the first is read, the rest is ignored");
  return scene;
}

Scene load_scene(const fs::path& path, const PovOptions& pov) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".yaml" && ext != ".yml" && ext != ".json" && ext != ".pov")
    throw Error(FileLoc{path.string()}, "unknown scene format '" + ext + "' (use .yaml, .yml, .json or .pov)");
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(FileLoc{path.string()}, "cannot open scene file (no such file)");
  if (fs::is_directory(path, ec)) throw Error(FileLoc{path.string()}, "is a directory, not a scene file");
  // A FIFO would block and /dev/zero would never end.
  if (!fs::is_regular_file(path, ec))
    throw Error(FileLoc{path.string()}, "is not a regular file (a FIFO, device or socket), not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(FileLoc{path.string()}, "cannot open scene file: " + system_reason(errno));
  Scene scene = [&] {
    std::ostringstream text;
    text << in.rdbuf();
    return ext == ".pov" ? parse_pov_scene(text.str(), path.string(), pov) : parse_scene(text.str(), path.string(), path.parent_path());
  }();
  give_back_free_heap();  // the text's and the parser's memory (util/large_pages.h)
  return scene;
}

}  // namespace strahl
