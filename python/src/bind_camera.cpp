// The camera and the render settings in Python (docs/python.md): the lecture's camera (position,
// look_at, up, fov or the image plane l, r, b, t, d; thin lens; shutter) and RenderSettings.

#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <string_view>

#include "bindings.h"
#include "convert.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/scene.h"
#include "strahl/scene/validate.h"

namespace strahl::python {
namespace {

// Enumerations as their scene-file names.
template <class Kind>
Kind kind_from(const std::string& name, std::optional<Kind> (*from_name)(std::string_view), const char* what,
               const std::string& names) {
  const std::optional<Kind> kind = from_name(name);
  if (!kind) throw Error(std::string("unknown ") + what + " '" + name + "' (" + names + ")");
  return *kind;
}

}  // namespace

void bind_camera(py::module_& m) {
  using FovAxis = CameraDescription::FovAxis;
  const CameraDescription d;
  py::class_<CameraDescription>(m, "Camera",
                                "The lecture's camera: eye position, look-at point, up vector and a field of view "
                                "(or the image plane l, r, b, t at distance d); thin lens and shutter.")
      .def(py::init([](const Vec3& position, const Vec3& look_at, const Vec3& up, double fov, const std::string& fov_axis,
                       const std::optional<std::tuple<double, double, double, double, double>>& image_plane,
                       double aperture, double focus_distance, const std::optional<Vec3>& focus_point,
                       const std::tuple<double, double>& shutter) {
             CameraDescription c;
             c.position = position;
             c.look_at = look_at;
             c.up = up;
             if (!(fov > 0 && fov < 180)) throw Error("fov must lie in (0, 180) degrees");
             c.fov_degrees = fov;
             if (fov_axis == "horizontal") c.fov_axis = FovAxis::Horizontal;
             else if (fov_axis == "vertical") c.fov_axis = FovAxis::Vertical;
             else throw Error("fov_axis must be 'horizontal' or 'vertical'");
             if (image_plane) {
               c.explicit_image_plane = true;
               std::tie(c.l, c.r, c.b, c.t, c.d) = *image_plane;
             }
             c.aperture = aperture;
             c.focus_distance = focus_distance;
             if (focus_point) {
               if (focus_distance != 0) throw py::type_error("give either focus_distance or focus_point, not both");
               c.has_focus_point = true;
               c.focus_point = *focus_point;
             }
             std::tie(c.shutter_open, c.shutter_close) = shutter;
             c.loc = caller_loc();
             // The checks compile() makes, now, so that a bad camera fails where it is made.
             Scene probe;
             probe.camera = c;
             probe.settings.width = probe.settings.height = 1;
             probe.add(Sphere(Vec3(0), 1, Material{}));
             (void)compile(probe);
             return c;
           }),
           py::kw_only(), py::arg("position") = py::make_tuple(d.position.x, d.position.y, d.position.z),
           py::arg("look_at") = py::make_tuple(d.look_at.x, d.look_at.y, d.look_at.z),
           py::arg("up") = py::make_tuple(d.up.x, d.up.y, d.up.z), py::arg("fov") = d.fov_degrees,
           py::arg("fov_axis") = "horizontal", py::arg("image_plane") = py::none(), py::arg("aperture") = 0.0,
           py::arg("focus_distance") = 0.0, py::arg("focus_point") = py::none(),
           py::arg("shutter") = py::make_tuple(0.0, 1.0))
      .def_readwrite("position", &CameraDescription::position)
      .def_readwrite("look_at", &CameraDescription::look_at)
      .def_readwrite("up", &CameraDescription::up)
      .def_readwrite("fov", &CameraDescription::fov_degrees)
      .def_property(
          "fov_axis", [](const CameraDescription& c) { return c.fov_axis == FovAxis::Horizontal ? "horizontal" : "vertical"; },
          [](CameraDescription& c, const std::string& axis) {
            if (axis == "horizontal") c.fov_axis = FovAxis::Horizontal;
            else if (axis == "vertical") c.fov_axis = FovAxis::Vertical;
            else throw Error("fov_axis must be 'horizontal' or 'vertical'");
          })
      .def_property(
          "image_plane",
          [](const CameraDescription& c) -> py::object {
            if (!c.explicit_image_plane) return py::none();
            return py::make_tuple(c.l, c.r, c.b, c.t, c.d);
          },
          [](CameraDescription& c, const std::optional<std::tuple<double, double, double, double, double>>& p) {
            c.explicit_image_plane = bool(p);
            if (p) std::tie(c.l, c.r, c.b, c.t, c.d) = *p;
          },
          "(l, r, b, t, d), or None for the field of view")
      .def_readwrite("aperture", &CameraDescription::aperture)
      .def_readwrite("focus_distance", &CameraDescription::focus_distance)
      .def_property(
          "focus_point",
          [](const CameraDescription& c) -> std::optional<Vec3> {
            if (!c.has_focus_point) return std::nullopt;
            return c.focus_point;
          },
          [](CameraDescription& c, const std::optional<Vec3>& p) {
            c.has_focus_point = bool(p);
            if (p) c.focus_point = *p;
          })
      .def_property(
          "shutter", [](const CameraDescription& c) { return py::make_tuple(c.shutter_open, c.shutter_close); },
          [](CameraDescription& c, const std::tuple<double, double>& s) { std::tie(c.shutter_open, c.shutter_close) = s; });
}

void bind_settings(py::module_& m) {
  py::class_<RenderSettings>(m, "RenderSettings",
                             "A scene's render settings (docs/scene-format.md, render); strahl.render's keyword "
                             "arguments override them for one render.")
      .def_readwrite("width", &RenderSettings::width)
      .def_readwrite("height", &RenderSettings::height)
      .def_readwrite("max_depth", &RenderSettings::max_depth)
      .def_readwrite("min_weight", &RenderSettings::min_weight)
      .def_readwrite("supersample", &RenderSettings::supersample)
      .def_readwrite("background", &RenderSettings::background)
      .def_readwrite("ambient_light", &RenderSettings::ambient_light)
      .def_readwrite("medium_ior", &RenderSettings::medium_ior)
      .def_property(
          "integrator", [](const RenderSettings& s) { return std::string(integrator_name(s.integrator)); },
          [](RenderSettings& s, const std::string& n) {
            s.integrator = kind_from(n, integrator_from_name, "integrator", kIntegratorNames);
          },
          "'whitted' (the lecture's recursive ray tracing) or 'path' (path tracing, global illumination)")
      .def_property(
          "accel", [](const RenderSettings& s) { return std::string(accel_name(s.accel)); },
          [](RenderSettings& s, const std::string& n) { s.accel = kind_from(n, accel_from_name, "accel", accel_names()); })
      .def_property(
          "sampler", [](const RenderSettings& s) { return sampler_name(s.sampling.sampler); },
          [](RenderSettings& s, const std::string& n) {
            s.sampling.sampler = kind_from(n, sampler_from_name, "sampler", kSamplerNames);
          })
      .def_property(
          "spp", [](const RenderSettings& s) { return s.sampling.spp; },
          [](RenderSettings& s, int v) { s.sampling.spp = v; }, "samples per pixel; 0: supersample² on the grid")
      .def_property(
          "seed", [](const RenderSettings& s) { return s.sampling.seed; },
          [](RenderSettings& s, std::uint64_t v) { s.sampling.seed = v; })
      .def_property(
          "filter", [](const RenderSettings& s) { return filter_name(s.sampling.filter.kind); },
          [](RenderSettings& s, const std::string& n) {
            s.sampling.filter.kind = kind_from(n, filter_from_name, "filter", kFilterNames);
          })
      .def_property(
          "filter_radius", [](const RenderSettings& s) { return s.sampling.filter.radius; },
          [](RenderSettings& s, double v) { s.sampling.filter.radius = v; })
      .def_property(
          "adaptive_min", [](const RenderSettings& s) { return s.sampling.adaptive_min; },
          [](RenderSettings& s, int v) { s.sampling.adaptive_min = v; })
      .def_property(
          "adaptive_threshold", [](const RenderSettings& s) { return s.sampling.adaptive_threshold; },
          [](RenderSettings& s, double v) { s.sampling.adaptive_threshold = v; });
}

}  // namespace strahl::python
