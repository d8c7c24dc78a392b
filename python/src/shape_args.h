#pragma once
// What the shapes' constructors share (python/src/bind_scene.cpp, bind_solids.cpp): a colour
// argument, a shape's material, a placement from scale/rotate/translate, and the deep copy that
// Scene.add makes of any shape.

#include <memory>
#include <optional>

#include "convert.h"
#include "strahl/scene/copy_object.h"  // copy_object: Scene.add, groups and CSG operands copy
#include "strahl/scene/scene.h"

namespace strahl::python {

// A colour: three numbers, or one number for grey.
Vec3 color_arg(const py::handle& value, const char* what);

// The material of a shape: `material`, or the default finish with `color`, or the default one.
Material object_material(const py::object& color, const std::optional<Material>& material);

// scale (one number or three), rotate (degrees about x, y, z), translate; `what` names the shape.
Transform make_transform(const py::object& scale, const Vec3& rotate, const Vec3& translate, const char* what);

}  // namespace strahl::python
