#pragma once
// How the viewer's mouse and keys move the camera. Every control edits the scene's own
// CameraDescription (position, look_at, up, fov), so the view on screen is always one that the
// printed YAML block (camera_yaml.h) renders again with `strahl`.
//
//   orbit   turns the eye about look_at (yaw about `up`, pitch towards or away from it): the
//           distance to look_at is kept, and the view never passes over the pole
//   pan     moves eye and look_at together across the image plane
//   dolly   moves the eye along the view direction towards or away from look_at
//   fly     moves eye and look_at together along right, up and forward
//   zoom    scales the field of view (or an explicit image plane)
//   focus   looks at a point; a thin-lens camera also focuses on it

#include "strahl/math/vec3.h"
#include "strahl/scene/scene.h"

namespace strahl::view {

// The camera's basis {u (right), v (up in the image), w (backwards)}, as compile() builds it.
struct ViewAxes {
  Vec3 u, v, w;
};
ViewAxes view_axes(const CameraDescription& c);

Real distance_to_look_at(const CameraDescription& c);

// Turns the eye about look_at by `yaw` radians about `up` (positive: counter-clockwise seen from
// above) and `pitch` radians towards `up` (positive: the eye rises). The angle between the view
// direction and `up` stays within [kMinPoleAngle, π − kMinPoleAngle].
void orbit(CameraDescription& c, Real yaw, Real pitch);
inline constexpr Real kMinPoleAngle = 0.01;  // radians

// Moves eye and look_at by dx·u + dy·v, with dx, dy in units of the distance to look_at.
void pan(CameraDescription& c, Real dx, Real dy);

// Multiplies the distance from the eye to look_at by `factor` (> 0; < 1 moves closer), along
// the view direction; look_at stays. The distance never falls below kMinDistance.
void dolly(CameraDescription& c, Real factor);
inline constexpr Real kMinDistance = 1e-6;

// Moves eye and look_at together by right·u + up·up_unit + forward·(−w).
void fly(CameraDescription& c, Real right, Real up, Real forward);

// Multiplies the field of view by `factor`, kept within [kMinFov, kMaxFov] degrees; an explicit
// image plane is scaled about its centre instead (the same zoom).
void zoom(CameraDescription& c, Real factor);
inline constexpr Real kMinFov = 1, kMaxFov = 170;

// The camera looks at `point` from where it is; a thin-lens camera (aperture > 0) focuses there
// (focus_distance follows look_at). A point at the eye changes nothing.
void focus_on(CameraDescription& c, const Vec3& point);

// The vertical field of view in radians (for the mouse: how far a pixel pans).
Real vertical_fov(const CameraDescription& c, int width, int height);

}  // namespace strahl::view
