#pragma once
// The parts of the module strahl._strahl (python/src/module.cpp puts them together).

#include <pybind11/pybind11.h>

namespace strahl::python {

namespace py = pybind11;

void bind_scene(py::module_& m);   // bind_scene.cpp: Material, Motion, Scene, load, and the five below
void bind_solids(py::module_& m);  // bind_solids.cpp: the solids and CSG (after bind_scene: SceneObject)
void bind_render(py::module_& m);  // bind_render.cpp: render, write, read, version

// The parts of bind_scene, in the order it binds them (a part's defaults use the types before it).
void bind_shapes(py::module_& m);    // bind_shapes.cpp: Sphere, Plane, Triangle, Mesh
void bind_instance(py::module_& m);  // bind_shapes.cpp: Instance
void bind_lights(py::module_& m);    // bind_lights.cpp: Light and its kinds
void bind_camera(py::module_& m);    // bind_camera.cpp: Camera
void bind_settings(py::module_& m);  // bind_camera.cpp: RenderSettings

}  // namespace strahl::python
