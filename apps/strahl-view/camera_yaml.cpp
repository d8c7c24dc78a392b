#include "camera_yaml.h"

#include <fmt/format.h>

namespace strahl::view {

namespace {
// fmt's "{}" is the shortest text that reads back as the same double.
std::string vec(const Vec3& v) { return fmt::format("[{}, {}, {}]", v.x, v.y, v.z); }
}  // namespace

std::string camera_yaml(const CameraDescription& c) {
  std::string s = "camera:\n";
  s += fmt::format("  position: {}\n", vec(c.position));
  s += fmt::format("  look_at: {}\n", vec(c.look_at));
  s += fmt::format("  up: {}\n", vec(c.up));
  if (c.explicit_image_plane) {
    s += fmt::format("  image_plane: {{l: {}, r: {}, b: {}, t: {}, d: {}}}\n", c.l, c.r, c.b, c.t, c.d);
  } else {
    s += fmt::format("  fov: {}\n", c.fov_degrees);
    s += fmt::format("  fov_axis: {}\n", c.fov_axis == CameraDescription::FovAxis::Horizontal ? "horizontal" : "vertical");
  }
  if (c.aperture > 0) s += fmt::format("  aperture: {}\n", c.aperture);
  if (c.has_focus_point) s += fmt::format("  focus_point: {}\n", vec(c.focus_point));
  else if (c.focus_distance > 0) s += fmt::format("  focus_distance: {}\n", c.focus_distance);
  if (c.shutter_open != 0 || c.shutter_close != 1) s += fmt::format("  shutter: [{}, {}]\n", c.shutter_open, c.shutter_close);
  return s;
}

}  // namespace strahl::view
