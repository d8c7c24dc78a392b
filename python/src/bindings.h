#pragma once
// The parts of the module strahl._strahl (python/src/module.cpp puts them together).

#include <pybind11/pybind11.h>

namespace strahl::python {

namespace py = pybind11;

void bind_scene(py::module_& m);   // bind_scene.cpp: materials, shapes, meshes, lights, camera, Scene, load
void bind_solids(py::module_& m);  // bind_solids.cpp: the solids and CSG (after bind_scene: SceneObject)
void bind_render(py::module_& m);  // bind_render.cpp: render, write, read, version

}  // namespace strahl::python
