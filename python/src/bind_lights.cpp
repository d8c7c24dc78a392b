// The lights in Python (docs/python.md): point, spot and directional lights and the rect, disk and
// sphere area lights, their radiance from an intensity or a total power.

#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <string>

#include "bindings.h"
#include "convert.h"
#include "shape_args.h"
#include "strahl/scene/scene.h"
#include "strahl/scene/validate.h"
#include "strahl/shading/area_light.h"

namespace strahl::python {
namespace {

// Area lights: radiance = colour × intensity, or from the total power (Φ = π·L·area).
Light finish_light(Light l, const Vec3& color, const std::optional<double>& intensity, const std::optional<double>& power,
                   int samples) {
  validate::non_negative(color, {}, "light color");
  if (intensity && power) throw py::type_error("give either intensity or power, not both");
  validate::int_range(samples, 1, 64, {}, "light samples");
  l.samples = samples;
  if (power) {
    validate::non_negative(*power, {}, "power");
    l.radiance = color * radiance_from_power(l, *power);
  } else {
    const double i = intensity.value_or(1.0);
    validate::non_negative(i, {}, "intensity");
    l.radiance = color * i;
  }
  return l;
}

// A point or spot light's fade (POV-Ray's; fade_power 0: none).
Light with_fade(Light l, double fade_distance, double fade_power) {
  validate::non_negative(fade_distance, {}, "light fade_distance");
  validate::non_negative(fade_power, {}, "light fade_power");
  if (fade_power > 0 && !(fade_distance > 0)) throw Error("a light's fade_power needs a positive fade_distance");
  l.fade_distance = fade_distance;
  l.fade_power = fade_power;
  return l;
}

}  // namespace

void bind_lights(py::module_& m) {
  const auto white = py::make_tuple(1, 1, 1);
  py::class_<Light>(m, "Light", "A light source; made by PointLight, SpotLight, DirectionalLight, RectLight, DiskLight, SphereLight.")
      .def_property_readonly("kind", [](const Light& l) { return light_kind_name(l.kind); })
      .def_readonly("position", &Light::position)
      .def_readonly("direction", &Light::direction)
      .def_readonly("radiance", &Light::radiance)
      .def_readonly("edge_u", &Light::edge_u)
      .def_readonly("edge_v", &Light::edge_v)
      .def_readonly("normal", &Light::normal)
      .def_readonly("radius", &Light::radius)
      .def_readonly("samples", &Light::samples)
      .def_readonly("angle", &Light::angle)
      .def_readonly("falloff", &Light::falloff)
      .def_readonly("tightness", &Light::tightness)
      .def_readonly("fade_distance", &Light::fade_distance)
      .def_readonly("fade_power", &Light::fade_power)
      .def("__repr__", [](const Light& l) {
        return std::string("strahl.Light(") + light_kind_name(l.kind) + ", position=" + repr(l.position) +
               ", radiance=" + repr(l.radiance) + ")";
      });
  m.def("PointLight", [](const Vec3& position, const py::object& color, double intensity, double fade_distance,
                         double fade_power) {
        validate::finite(position, {}, "light position");
        const Vec3 c = color_arg(color, "light color");
        validate::non_negative(c, {}, "light color");
        validate::non_negative(intensity, {}, "intensity");
        return with_fade(point_light(position, c, intensity), fade_distance, fade_power);
      }, py::arg("position"), py::arg("color") = white, py::arg("intensity") = 1.0, py::kw_only(),
      py::arg("fade_distance") = 0.0, py::arg("fade_power") = 0.0,
      "A point light of intensity colour × intensity; as in the lecture, it does not fall off with distance "
      "unless fade_power > 0 (POV-Ray's fade: 2/(1 + (d/fade_distance)^fade_power)).");
  m.def("SpotLight", [](const Vec3& position, const Vec3& point_at, const py::object& color, double intensity,
                        double angle, double falloff, double tightness, double fade_distance, double fade_power) {
        validate::finite(position, {}, "light position");
        validate::finite(point_at, {}, "spotlight point_at");
        validate::non_zero(point_at - position, {}, "spotlight direction (point_at − position)");
        const Vec3 c = color_arg(color, "light color");
        validate::non_negative(c, {}, "light color");
        validate::non_negative(intensity, {}, "intensity");
        validate::in_range(angle, 0, 90, {}, "spotlight angle");
        validate::in_range(falloff, 0, 90, {}, "spotlight falloff");
        validate::non_negative(tightness, {}, "spotlight tightness");
        return with_fade(spot_light(position, point_at - position, angle, falloff, tightness, c, intensity), fade_distance,
                         fade_power);
      }, py::arg("position"), py::arg("point_at"), py::arg("color") = white, py::arg("intensity") = 1.0, py::kw_only(),
      py::arg("angle") = 30.0, py::arg("falloff") = 45.0, py::arg("tightness") = 0.0, py::arg("fade_distance") = 0.0,
      py::arg("fade_power") = 0.0,
      "A spotlight (POV-Ray's): a point light at `position` shining towards `point_at`, at full strength within "
      "`angle` degrees of that axis, none beyond `falloff` degrees, a smooth step between; all times "
      "cos(θ)^tightness; a fade with distance as PointLight's.");
  m.def("DirectionalLight", [](const Vec3& direction, const py::object& color, double intensity) {
        validate::non_zero(direction, {}, "light direction");
        const Vec3 c = color_arg(color, "light color");
        validate::non_negative(c, {}, "light color");
        validate::non_negative(intensity, {}, "intensity");
        return directional_light(direction, c, intensity);
      }, py::arg("direction"), py::arg("color") = white, py::arg("intensity") = 1.0,
      "A light from infinitely far away; `direction` is the way its light travels.");
  m.def("RectLight", [](const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v, const py::object& color,
                        std::optional<double> intensity, std::optional<double> power, int samples) {
        validate::finite(corner, {}, "light corner");
        validate::non_zero(edge_u, {}, "edge_u");
        validate::non_zero(edge_v, {}, "edge_v");
        if (std::fabs(dot(normalize(edge_u), normalize(edge_v))) > 1e-6) throw Error("rect light edges must be perpendicular");
        Light l = rect_light(corner, edge_u, edge_v, Vec3(1), samples);
        l.normal = normalize(l.normal);  // (for radiance_from_power; compile() sets it again from the edges)
        return finish_light(l, color_arg(color, "light color"), intensity, power, samples);
      }, py::arg("corner"), py::arg("edge_u"), py::arg("edge_v"), py::arg("color") = white, py::kw_only(),
      py::arg("intensity") = py::none(), py::arg("power") = py::none(), py::arg("samples") = 4,
      "A rectangular area light; it emits towards edge_u × edge_v.");
  m.def("DiskLight", [](const Vec3& center, const Vec3& normal, double radius, const py::object& color,
                        std::optional<double> intensity, std::optional<double> power, int samples) {
        validate::finite(center, {}, "light center");
        validate::non_zero(normal, {}, "light normal");
        validate::positive(radius, {}, "light radius");
        const Light l = disk_light(center, normal, radius, Vec3(1), samples);  // compile() normalises the normal
        return finish_light(l, color_arg(color, "light color"), intensity, power, samples);
      }, py::arg("center"), py::arg("normal"), py::arg("radius"), py::arg("color") = white, py::kw_only(),
      py::arg("intensity") = py::none(), py::arg("power") = py::none(), py::arg("samples") = 4,
      "A disk-shaped area light emitting towards `normal`.");
  m.def("SphereLight", [](const Vec3& center, double radius, const py::object& color, std::optional<double> intensity,
                          std::optional<double> power, int samples) {
        validate::finite(center, {}, "light center");
        validate::positive(radius, {}, "light radius");
        const Light l = sphere_light(center, radius, Vec3(1), samples);
        return finish_light(l, color_arg(color, "light color"), intensity, power, samples);
      }, py::arg("center"), py::arg("radius"), py::arg("color") = white, py::kw_only(),
      py::arg("intensity") = py::none(), py::arg("power") = py::none(), py::arg("samples") = 4,
      "A spherical area light emitting from its whole surface.");
}

}  // namespace strahl::python
