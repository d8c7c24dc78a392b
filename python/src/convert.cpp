#include "convert.h"

#include <frameobject.h>
#include <pybind11/eval.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <sstream>
#include <thread>

#include "strahl/util/cancel.h"

namespace strahl::python {

std::string repr(const Vec3& v) {
  std::ostringstream out;
  out << '(' << v.x << ", " << v.y << ", " << v.z << ')';
  return out.str();
}

FileLoc caller_loc() {
  FileLoc loc;
  PyFrameObject* frame = PyEval_GetFrame();  // borrowed
  if (frame == nullptr) return loc;
  PyCodeObject* code = PyFrame_GetCode(frame);  // new reference
  const py::object file = py::reinterpret_steal<py::object>(PyObject_GetAttrString(reinterpret_cast<PyObject*>(code), "co_filename"));
  Py_DECREF(code);
  if (!file || !PyUnicode_Check(file.ptr())) {
    PyErr_Clear();
    return loc;
  }
  loc.file = file.cast<std::string>();
  loc.line = PyFrame_GetLineNumber(frame);
  return loc;
}

py::array_t<float> to_numpy(const Image& image, int channels) {
  const auto h = py::ssize_t(image.height()), w = py::ssize_t(image.width());
  py::array_t<float> out = channels == 3 ? py::array_t<float>({h, w, py::ssize_t(3)}) : py::array_t<float>({h, w});
  float* dst = out.mutable_data();
  const auto& px = image.pixels();
  if (channels == 3) {
    static_assert(sizeof(Rgb) == 3 * sizeof(float));
    std::memcpy(dst, px.data(), px.size() * sizeof(Rgb));
  } else {
    for (std::size_t i = 0; i < px.size(); ++i) dst[i] = px[i].r;
  }
  return out;
}

Image from_numpy(const py::handle& object) {
  if (!py::isinstance<py::array>(object)) throw py::type_error("an image must be a numpy array (height × width × 3, or height × width)");
  const py::array any = py::reinterpret_borrow<py::array>(object);
  const char kind = any.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b')
    throw py::type_error("an image must hold numbers (got dtype " + py::str(any.dtype()).cast<std::string>() + ")");
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(object);
  if (!a) throw py::type_error("an image must be a numpy array of numbers");
  const bool rgb = a.ndim() == 3 && a.shape(2) == 3;
  if (!rgb && a.ndim() != 2) throw py::value_error("an image must have the shape (height, width, 3) or (height, width)");
  if (a.shape(0) < 1 || a.shape(1) < 1 || a.shape(0) > 1 << 24 || a.shape(1) > 1 << 24)
    throw py::value_error("an image must be between 1 and 16777216 pixels wide and high");
  const int w = int(a.shape(1)), h = int(a.shape(0));
  Image image(w, h);
  const float* src = a.data();
  for (int row = 0; row < h; ++row)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(row) * std::size_t(w) + std::size_t(x);
      image.at(x, row) = rgb ? Rgb{src[3 * i], src[3 * i + 1], src[3 * i + 2]} : Rgb{src[i], src[i], src[i]};
    }
  return image;
}

namespace {
// The loaders' cancel flag while the module is loaded (util/cancel.h); set only while a load
// that a signal handler interrupted winds down.
std::atomic<bool> g_cancel{false};
std::mutex g_cancel_mutex;  // loads in several Python threads: one at a time resets the flag
int g_interrupted_loads = 0;
}  // namespace

std::optional<py::error_already_set> wait_interruptible(const std::function<void()>& work) {
  set_cancel_flag(&g_cancel);  // (idempotent; the module owns the process-wide flag)
  std::optional<py::error_already_set> raised;
  std::mutex mutex;
  std::condition_variable done_cv;
  bool done = false;
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      work();
      {
        const std::lock_guard<std::mutex> lock(mutex);
        done = true;
      }
      done_cv.notify_all();
    });
    bool cancelling = false;
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(mutex);
        if (done_cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) break;
      }
      if (cancelling) continue;
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {
        raised.emplace();
        cancelling = true;
        const std::lock_guard<std::mutex> lock(g_cancel_mutex);
        ++g_interrupted_loads;
        g_cancel.store(true);
      }
    }
    worker.join();
    if (cancelling) {
      const std::lock_guard<std::mutex> lock(g_cancel_mutex);
      if (--g_interrupted_loads == 0) g_cancel.store(false);
    }
  }
  return raised;
}

void register_error(py::module_& m) {
  // Defined in Python so that it carries the location as attributes (file, line, column; None
  // where unknown) besides the message the CLI prints.
  py::dict scope;
  scope["ValueError"] = py::module_::import("builtins").attr("ValueError");
  py::exec(R"(
class Error(ValueError):
    """A bad scene or argument, or a failed read or write: the message the strahl CLI prints,
    with the location (file, line, column; None where unknown) as attributes."""

    def __init__(self, message, file=None, line=None, column=None):
        super().__init__(message)
        self.message = message
        self.file = file
        self.line = line
        self.column = column
)", scope);
  py::object error = scope["Error"];
  error.attr("__module__") = "strahl";
  m.attr("Error") = error;
  static py::handle error_type = error.inc_ref();  // lives as long as the interpreter
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const strahl::Error& e) {
      const FileLoc& loc = e.loc();
      py::object none = py::none();
      py::object exc = error_type(e.what(), loc.file.empty() ? none : py::str(loc.file),
                                  loc.line > 0 ? py::object(py::int_(loc.line)) : none,
                                  loc.column > 0 ? py::object(py::int_(loc.column)) : none);
      PyErr_SetObject(error_type.ptr(), exc.ptr());
    } catch (const Cancelled&) {
      // A load stopped by the cancel flag (Ctrl-C in this or, the flag being process-wide,
      // another Python thread's load).
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });
}

}  // namespace strahl::python
