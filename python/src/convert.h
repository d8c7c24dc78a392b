#pragma once
// Conversions between Python values and strahl's: a Vec3 is any sequence of three numbers (tuple,
// list, numpy array) and comes back as a tuple; images are numpy float32 arrays height × width × 3
// (or height × width), row 0 at the top, linear RGB.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <functional>
#include <optional>
#include <string>

#include "strahl/image/image.h"
#include "strahl/math/vec3.h"
#include "strahl/util/error.h"

namespace pybind11::detail {

template <>
struct type_caster<strahl::Vec3> {
  PYBIND11_TYPE_CASTER(strahl::Vec3, const_name("tuple[float, float, float]"));

  bool load(handle src, bool) {
    if (!src || PyUnicode_Check(src.ptr()) || PyBytes_Check(src.ptr()) || !PySequence_Check(src.ptr())) return false;
    const Py_ssize_t n = PySequence_Size(src.ptr());
    if (n != 3) {
      PyErr_Clear();
      return false;
    }
    double v[3];
    for (Py_ssize_t i = 0; i < 3; ++i) {
      object item = reinterpret_steal<object>(PySequence_GetItem(src.ptr(), i));
      // Numbers only: a str or a nested sequence is not a coordinate (PyFloat_AsDouble would
      // accept any object with __float__, which numbers and numpy scalars have).
      if (!item || PyUnicode_Check(item.ptr()) || !PyNumber_Check(item.ptr())) {
        PyErr_Clear();
        return false;
      }
      v[i] = PyFloat_AsDouble(item.ptr());
      if (v[i] == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        return false;
      }
    }
    value = strahl::Vec3(v[0], v[1], v[2]);
    return true;
  }

  static handle cast(const strahl::Vec3& v, return_value_policy, handle) {
    return make_tuple(v.x, v.y, v.z).release();
  }
};

}  // namespace pybind11::detail

namespace strahl::python {

namespace py = pybind11;

// (x, y, z) as text, for __repr__.
std::string repr(const Vec3& v);

// Where the Python code that is running now is (file and line), for objects built in Python:
// compile() names it in its errors as a scene file's objects name their line.
FileLoc caller_loc();

// Images to numpy: H × W × 3 float32 (channels = 3) or H × W, the first channel (channels = 1).
py::array_t<float> to_numpy(const Image& image, int channels = 3);
// numpy (H × W × 3 or H × W, any real dtype) to an image; throws py::type_error / value_error.
Image from_numpy(const py::handle& array);

// Runs work() — reading a scene or mesh file — in a thread of its own while this thread waits
// without the GIL, running Python's signal handlers every 50 ms. When one raises
// (KeyboardInterrupt on Ctrl-C), the loaders' cancel flag (util/cancel.h) is set, and the
// exception is raised once work() has stopped. The GIL must be held; work() must not touch
// Python objects.
template <class T>
T interruptible(const std::function<T()>& work);

// The Python exception strahl.Error (a ValueError) with the attributes file, line, column and
// message; set up once by the module.
void register_error(py::module_& m);

// The flag interruptible() sets (the module makes it the loaders' cancel flag), and the loop it
// waits in: returns the exception a signal handler raised, if one did (after work() ended).
std::optional<py::error_already_set> wait_interruptible(const std::function<void()>& work);

template <class T>
T interruptible(const std::function<T()>& work) {
  std::optional<T> result;
  std::exception_ptr failure;
  std::optional<py::error_already_set> raised = wait_interruptible([&] {
    try {
      result.emplace(work());
    } catch (...) {
      failure = std::current_exception();
    }
  });
  if (raised) throw std::move(*raised);
  if (failure) std::rethrow_exception(failure);
  return std::move(*result);
}

}  // namespace strahl::python
