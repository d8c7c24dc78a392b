#include "camera_control.h"

#include <algorithm>
#include <cmath>

#include "strahl/math/frame.h"

namespace strahl::view {

ViewAxes view_axes(const CameraDescription& c) {
  const Frame f = Frame::look_at(c.position, c.look_at, c.up);
  return {f.u, f.v, f.w};
}

Real distance_to_look_at(const CameraDescription& c) { return length(c.position - c.look_at); }

void orbit(CameraDescription& c, Real yaw, Real pitch) {
  const Vec3 up = normalize(c.up);
  const Vec3 offset = c.position - c.look_at;  // from look_at to the eye
  const Real distance = length(offset);
  if (!(distance > 0)) return;
  // Spherical coordinates about `up`: the polar angle from up, and the horizontal direction.
  const Real along = std::clamp(dot(offset, up) / distance, Real(-1), Real(1));
  const Real polar = std::clamp(std::acos(along) - pitch, kMinPoleAngle, kPi - kMinPoleAngle);
  Vec3 horizontal = offset - up * dot(offset, up);
  if (!(length_squared(horizontal) > 0)) horizontal = cross(up, view_axes(c).u);  // on the pole
  horizontal = normalize(horizontal);
  // Rodrigues' rotation about up of a vector perpendicular to it.
  const Vec3 turned = horizontal * std::cos(yaw) + cross(up, horizontal) * std::sin(yaw);
  c.position = c.look_at + (up * std::cos(polar) + normalize(turned) * std::sin(polar)) * distance;
}

void pan(CameraDescription& c, Real dx, Real dy) {
  const ViewAxes a = view_axes(c);
  const Vec3 shift = (a.u * dx + a.v * dy) * distance_to_look_at(c);
  c.position += shift;
  c.look_at += shift;
}

void dolly(CameraDescription& c, Real factor) {
  const Vec3 offset = c.position - c.look_at;
  const Real distance = length(offset);
  if (!(distance > 0) || !(factor > 0)) return;
  const Real wanted = std::max(distance * factor, kMinDistance);
  c.position = c.look_at + offset * (wanted / distance);
}

void fly(CameraDescription& c, Real right, Real up, Real forward) {
  const ViewAxes a = view_axes(c);
  const Vec3 shift = a.u * right + normalize(c.up) * up - a.w * forward;
  c.position += shift;
  c.look_at += shift;
}

void zoom(CameraDescription& c, Real factor) {
  if (!(factor > 0)) return;
  if (c.explicit_image_plane) {
    const Real cx = (c.l + c.r) / 2, cy = (c.b + c.t) / 2;
    c.l = cx + (c.l - cx) * factor;
    c.r = cx + (c.r - cx) * factor;
    c.b = cy + (c.b - cy) * factor;
    c.t = cy + (c.t - cy) * factor;
    return;
  }
  c.fov_degrees = std::clamp(c.fov_degrees * factor, kMinFov, kMaxFov);
}

void focus_on(CameraDescription& c, const Vec3& point) {
  if (!(length_squared(point - c.position) > 0)) return;
  c.look_at = point;
  // The focus follows look_at: the default of a lens camera without focus_distance/focus_point.
  c.focus_distance = 0;
  c.has_focus_point = false;
}

Real vertical_fov(const CameraDescription& c, int width, int height) {
  if (c.explicit_image_plane) return 2 * std::atan((c.t - c.b) / (2 * c.d));
  const Real half = std::tan(c.fov_degrees * kPi / 360);
  const Real aspect = Real(width) / Real(height);
  return 2 * std::atan(c.fov_axis == CameraDescription::FovAxis::Horizontal ? half / aspect : half);
}

}  // namespace strahl::view
