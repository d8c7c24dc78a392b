// strahl._strahl: the compiled part of the Python package strahl (python/strahl/__init__.py
// re-exports it; docs/python.md).

#include "bindings.h"
#include "convert.h"

PYBIND11_MODULE(_strahl, m) {
  m.doc() = "strahl, a Whitted-style ray tracer: the lecture's scene API, scene files and rendering (docs/python.md)";
  strahl::python::register_error(m);
  strahl::python::bind_scene(m);
  strahl::python::bind_solids(m);
  strahl::python::bind_render(m);
}
