#pragma once
// Copies of scene objects through the base class (Python's Scene.add, a group's moving shapes).

#include <memory>

#include "strahl/scene/scene.h"

namespace strahl {

// A copy of any shape a scene file or the API makes (a CSG tree with copies of its operands);
// nullptr for one it cannot copy (an instance: its group belongs to its scene).
std::unique_ptr<SceneObject> copy_object(const SceneObject& object);

}  // namespace strahl
