#pragma once
// The camera as a `camera:` block of the scene format (docs/scene-format.md), ready to paste
// into a scene file. Numbers are written in the shortest form that reads back as the same
// double, so the block renders exactly the view the viewer shows.

#include <string>

#include "strahl/scene/scene.h"

namespace strahl::view {

// Lines "camera:\n  position: [x, y, z]\n …", each ending in a newline.
std::string camera_yaml(const CameraDescription& c);

}  // namespace strahl::view
