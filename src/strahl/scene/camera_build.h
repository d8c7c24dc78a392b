#pragma once
// The lecture's camera (e, {u, v, w}, l, r, b, t, d, n_x × n_y) from its description: what
// compile() does for the scene's camera, and what the viewer does for every new view and
// resolution without compiling the scene again.

#include "strahl/camera/camera.h"
#include "strahl/scene/scene.h"

namespace strahl {

// Checks the description (throws strahl::Error naming c.loc) and builds the camera for an
// nx × ny image.
Camera build_camera(const CameraDescription& c, int nx, int ny);

}  // namespace strahl
