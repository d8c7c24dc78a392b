// A YAML scene's settings (yaml_reader.h): render and sampling settings, the camera, materials and
// lights (point, spot, directional, and the rect, disk and sphere area lights).

#include "strahl/scene/yaml_reader.h"

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "strahl/scene/validate.h"
#include "strahl/shading/area_light.h"

namespace strahl {

void YamlReader::render(const YAML::Node& n, RenderSettings& s) const {
  map(n, "render");
  keys(n, {"width", "height", "max_depth", "min_weight", "ray_budget", "supersample", "background", "ambient_light", "medium_ior",
           "integrator", "accel", "sampler", "spp", "seed", "filter", "filter_radius", "adaptive_min", "adaptive_threshold"},
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
  if (const auto v = n["integrator"]) {
    const std::optional<IntegratorKind> kind = integrator_from_name(scalar(v, "integrator"));
    if (!kind) fail(v, "unknown integrator '" + v.Scalar() + "' (" + kIntegratorNames + ")");
    s.integrator = *kind;
  }
  if (const auto v = n["accel"]) {
    const std::optional<AccelKind> kind = accel_from_name(scalar(v, "accel"));
    if (!kind) fail(v, "unknown accel '" + v.Scalar() + "' (" + accel_names() + ")");
    s.accel = *kind;
  }
  sampling(n, s.sampling);
}

void YamlReader::sampling(const YAML::Node& n, SamplingSettings& s) const {
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

void YamlReader::camera(const YAML::Node& n, CameraDescription& c) const {
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

Material YamlReader::material(const YAML::Node& n) const {
  map(n, "material");
  keys(n, {"color", "ambient", "diffuse", "specular", "shininess", "reflectivity", "transparency", "ior", "fresnel",
           "filter", "checker", "roughness", "image", "emission"},
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
  if (const auto v = n["emission"]) m.emission = color(v, "emission");
  if (const auto c = n["checker"]) {
    map(c, "checker");
    keys(c, {"size", "color"}, "checker");
    m.checker_size = positive(required(c, "size", "checker"), "checker size");
    if (const auto v = c["color"]) m.checker_color = color(v, "checker color");
  }
  if (const auto v = n["image"]) {
    if (n["checker"]) fail(v, "a material has a checker or an image, not both");
    m.texture = image_texture(v);
  }
  return m;
}

// `image: {file, mapping, interpolate, once, linear, placement keys}` (docs/scene-format.md,
// "Image textures"): the texture is added to the reader's list; returns its index.
std::uint32_t YamlReader::image_texture(const YAML::Node& n) const {
  map(n, "image");
  keys(n, {"file", "mapping", "interpolate", "once", "linear", "scale", "rotate", "translate", "matrix", "transform"},
       "image");
  ImageTexture t;
  t.loc = loc(n);
  const YAML::Node f = required(n, "file", "image");
  const bool linear = n["linear"] ? boolean(n["linear"], "image linear") : false;
  t.file = base_dir_ / scalar(f, "image file");
  auto [it, fresh] = images_.try_emplace({t.file, linear}, nullptr);
  if (fresh) {
    try {
      it->second = read_texture_image(t.file, linear);
    } catch (const Error& e) {
      images_.erase(it);
      fail(f, std::string("image: ") + e.what());
    }
  }
  t.image = it->second;
  if (const auto v = n["mapping"]) {
    const std::string mapping = scalar(v, "image mapping");
    if (!image_mapping_from(mapping, t.mapping))
      fail(v, "unknown image mapping '" + mapping + "' (" + kImageMappingNames + ")");
  }
  if (const auto v = n["interpolate"]) {
    const std::string how = scalar(v, "image interpolate");
    if (!image_interpolate_from(how, t.bilinear))
      fail(v, "unknown image interpolate '" + how + "' (" + kImageInterpolateNames + ")");
  }
  if (const auto v = n["once"]) t.once = boolean(v, "image once");
  t.placement = placement(n, "image ");
  if (textures_.size() >= kNoTexture) fail(n, "too many image textures");
  textures_.push_back(std::move(t));
  return static_cast<std::uint32_t>(textures_.size() - 1);
}

// `material: name` refers to the materials section; a map defines one in place.
Material YamlReader::object_material(const YAML::Node& object) const {
  const YAML::Node n = object["material"];
  if (!n) return Material{};
  if (n.IsScalar()) {
    const auto it = materials_.find(n.Scalar());
    if (it == materials_.end()) fail(n, "unknown material '" + n.Scalar() + "'");
    return it->second;
  }
  return material(n);
}

void YamlReader::light(const YAML::Node& n, Scene& scene) const {
  map(n, "light");
  const std::string type = scalar(required(n, "type", "light"), "light type");
  const Vec3 c = n["color"] ? color(n["color"], "light color") : Vec3(1);
  const Real intensity = n["intensity"] ? non_negative(n["intensity"], "intensity") : Real(1);
  if (type == "point") {
    keys(n, {"type", "position", "color", "intensity", "fade_distance", "fade_power"}, "point light");
    Light l = point_light(vec3(required(n, "position", "point light"), "light position"), c, intensity);
    fade(n, l);
    scene.add(l, loc(n));
  } else if (type == "directional") {
    keys(n, {"type", "direction", "color", "intensity"}, "directional light");
    const YAML::Node d = required(n, "direction", "directional light");
    const Vec3 dir = vec3(d, "light direction");
    validate::non_zero(dir, loc(d), "light direction");
    scene.add(directional_light(dir, c, intensity), loc(n));
  } else if (type == "spot") {
    spot_light(n, c, intensity, scene);
  } else if (type == "rect" || type == "disk" || type == "sphere") {
    area_light(n, type, c, scene);
  } else {
    fail(n["type"], "unknown light type '" + type + "' (point, spot, directional, rect, disk or sphere)");
  }
}

// A spotlight: its axis from `point_at` or `direction` (one of the two), its angles in degrees.
void YamlReader::spot_light(const YAML::Node& n, const Vec3& c, Real intensity, Scene& scene) const {
  keys(n, {"type", "position", "point_at", "direction", "angle", "falloff", "tightness", "color", "intensity",
           "fade_distance", "fade_power"},
       "spot light");
  const Vec3 position = vec3(required(n, "position", "spot light"), "light position");
  if (n["point_at"] && n["direction"]) fail(n["direction"], "a spot light takes point_at or direction, not both");
  if (!n["point_at"] && !n["direction"]) fail(n, "a spot light needs point_at or direction");
  const YAML::Node aim = n["point_at"] ? n["point_at"] : n["direction"];
  const Vec3 axis = n["point_at"] ? vec3(aim, "spotlight point_at") - position : vec3(aim, "spotlight direction");
  validate::non_zero(axis, loc(aim), n["point_at"] ? "spotlight direction (point_at − position)" : "spotlight direction");
  const auto degrees = [&](const char* key, Real fallback) {
    const YAML::Node v = n[key];
    if (!v) return fallback;
    const Real a = number(v, std::string("spotlight ") + key);
    if (!(a >= 0 && a <= 90)) fail(v, std::string("spotlight ") + key + " must lie in [0, 90] degrees");
    return a;
  };
  const Real angle = degrees("angle", 30), falloff = degrees("falloff", 45);
  const Real tightness = n["tightness"] ? non_negative(n["tightness"], "spotlight tightness") : Real(0);
  Light l = strahl::spot_light(position, axis, angle, falloff, tightness, c, intensity);
  fade(n, l);
  scene.add(l, loc(n));
}

// A point or spot light's fade with distance (POV-Ray's): fade_power > 0 turns it on.
void YamlReader::fade(const YAML::Node& n, Light& l) const {
  if (const auto v = n["fade_distance"]) l.fade_distance = non_negative(v, "light fade_distance");
  if (const auto v = n["fade_power"]) l.fade_power = non_negative(v, "light fade_power");
  if (l.fade_power > 0 && !(l.fade_distance > 0))
    fail(n["fade_power"], "a light's fade_power needs a positive fade_distance (the distance where the fade is 1)");
}

// Area lights: radiance L = color × intensity, or from `power` Φ (one-sided: Φ = π·L·area).
void YamlReader::area_light(const YAML::Node& n, const std::string& type, const Vec3& c, Scene& scene) const {
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

}  // namespace strahl
