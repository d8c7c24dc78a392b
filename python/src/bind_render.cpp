// strahl.render: compile the scene with the keyword arguments over its settings, then run one
// RenderJob (render/render_job.h) on the CPU back end (or the GPU's: device) in a thread of its own, while the calling
// thread, without the GIL, waits for it: every 50 ms it takes the GIL, runs Python's signal
// handlers (Ctrl-C raises KeyboardInterrupt there, and the job is cancelled) and reports progress.
// Also write, read and the version.

#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

#include "bindings.h"
#include "convert.h"
#include "strahl/cuda/cuda_backend.h"
#include "strahl/image/image_io.h"
#include "strahl/render/aov.h"
#include "strahl/render/cpu_backend.h"
#include "strahl/render/explain.h"
#include "strahl/render/render_job.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/scene_hash.h"
#include "strahl/sampling/pixel_sampler.h"
#include "strahl/scene/scene.h"
#include "strahl/scene/validate.h"
#include "strahl/version.h"

namespace strahl::python {

namespace {

// The keyword arguments of strahl.render that override the scene's settings (the CLI's flags).
struct Overrides {
  std::optional<int> width, height, spp, max_depth, supersample, adaptive_min;
  std::optional<std::string> sampler, filter, accel;
  std::optional<std::uint64_t> seed;
  std::optional<double> filter_radius, adaptive_threshold;
  double time_limit = 0;
  std::optional<std::string> integrator;
};

template <class Kind>
Kind named(const std::string& name, std::optional<Kind> (*from_name)(std::string_view), const char* what,
           const std::string& names) {
  const std::optional<Kind> kind = from_name(name);
  if (!kind) throw Error(std::string("unknown ") + what + " '" + name + "' (" + names + ")");
  return *kind;
}

void apply(const Overrides& o, RenderSettings& s) {
  if (o.width) s.width = *o.width;
  if (o.height) s.height = *o.height;
  if (o.max_depth) s.max_depth = *o.max_depth;
  if (o.supersample) s.supersample = *o.supersample;
  if (o.accel) s.accel = named(*o.accel, accel_from_name, "accel", accel_names());
  if (o.integrator) s.integrator = named(*o.integrator, integrator_from_name, "integrator", kIntegratorNames);
  SamplingSettings& p = s.sampling;
  if (o.sampler) p.sampler = named(*o.sampler, sampler_from_name, "sampler", kSamplerNames);
  if (o.spp) {
    validate::int_range(*o.spp, 1, kMaxSpp, {}, "spp");
    p.spp = *o.spp;
  }
  if (o.seed) p.seed = *o.seed;
  if (o.filter) p.filter.kind = named(*o.filter, filter_from_name, "filter", kFilterNames);
  if (o.filter_radius) p.filter.radius = *o.filter_radius;
  if (o.adaptive_min) p.adaptive_min = *o.adaptive_min;
  if (o.adaptive_threshold) p.adaptive_threshold = *o.adaptive_threshold;
  // As the CLI: a time limit without a sample count renders until the limit.
  if (o.time_limit > 0 && !o.spp && p.spp == 0) p.spp = 65536;
}

// compile() with the overrides applied to the scene's settings for this call only.
RenderScene compile_with(Scene& scene, const Overrides& o) {
  const RenderSettings saved = scene.settings;
  try {
    apply(o, scene.settings);
    RenderScene out = compile(scene);
    scene.settings = saved;
    return out;
  } catch (...) {
    scene.settings = saved;
    throw;
  }
}

// Runs the job in a thread of its own; this thread waits without the GIL and, every 50 ms, with
// it: Python's signal handlers (an exception from one — KeyboardInterrupt — cancels the job and
// is raised once the job has stopped) and the progress callback.
void run_job(RenderJob& job, TileBackend& backend, const py::object& progress) {
  std::mutex mutex;
  std::condition_variable finished_cv;
  bool finished = false;
  std::exception_ptr failure;
  std::optional<py::error_already_set> raised;
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      try {
        job.run(backend);
      } catch (...) {
        failure = std::current_exception();
      }
      {
        const std::lock_guard<std::mutex> lock(mutex);
        finished = true;
      }
      finished_cv.notify_all();
    });
    long reported = -1;
    for (;;) {
      bool end = false;
      {
        std::unique_lock<std::mutex> lock(mutex);
        end = finished_cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return finished; });
      }
      bool stop = false;
      {
        py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() != 0) {
          raised.emplace();  // fetches the exception a handler raised
          stop = true;
        } else if (!progress.is_none()) {
          const long d = job.samples_done() > 0 ? long(job.samples_done()) : 0;
          const long t = long(job.samples_planned());
          if (d != reported) {
            reported = d;
            try {
              progress(d, t);
            } catch (py::error_already_set& e) {
              raised.emplace(std::move(e));
              stop = true;
            }
          }
        }
      }
      if (stop) {
        job.cancel();
        break;
      }
      if (end) break;
    }
    worker.join();
  }
  if (raised) throw std::move(*raised);
  if (failure) std::rethrow_exception(failure);
}

// The GPU's back end as `device` asks for it: none for "cpu"; for "cuda" the back end or an error;
// for "auto" the back end, or none and a RuntimeWarning saying why the CPU renders.
std::unique_ptr<CudaBackend> open_gpu(const std::string& device, const RenderScene& rs) {
  if (device == "cpu") return nullptr;
  const AccelKind kind = rs.accel.kind;
  if (device == "cuda" && !gpu_traverses(kind))
    throw Error("device='cuda' renders with accel 'bvh', 'kdtree', 'octree' or 'naive', not '" +
                std::string(accel_name(kind)) + "'");
  std::string why;
  std::unique_ptr<CudaBackend> gpu = CudaBackend::create(rs, why);
  if (gpu) return gpu;
  if (device == "cuda") throw Error("device='cuda': " + why);
  const std::string note = "device='auto': " + why + "; rendering on the CPU";
  if (PyErr_WarnEx(PyExc_RuntimeWarning, note.c_str(), 2) != 0) throw py::error_already_set();  // warnings as errors
  return nullptr;
}

py::object render(Scene& scene, const Overrides& o, int threads, int tile_size, const py::object& progress,
                  const std::vector<std::string>& aovs, const std::string& device) {
  validate::int_range(threads, 0, 4096, {}, "threads");
  if (device != "cpu" && device != "cuda" && device != "auto")
    throw Error("unknown device '" + device + "' (cpu, cuda, auto)");
  validate::int_range(tile_size, 1, 4096, {}, "tile_size");
  validate::non_negative(o.time_limit, {}, "time_limit");
  for (const std::string& a : aovs)
    if (a != "depth" && a != "normal" && a != "albedo" && a != "id")
      throw Error("unknown aov '" + a + "' (depth, normal, albedo, id)");
  if (!progress.is_none() && !PyCallable_Check(progress.ptr())) throw py::type_error("progress must be callable or None");

  const RenderScene rs = compile_with(scene, o);
  JobOptions options;
  options.tile_size = tile_size;
  options.time_limit = o.time_limit;
  RenderJob job(rs.view(), rs.sampling, std::move(options));
  const std::unique_ptr<CudaBackend> gpu = open_gpu(device, rs);
  CpuBackend cpu(threads);
  run_job(job, gpu ? static_cast<TileBackend&>(*gpu) : cpu, progress);
  if (gpu && !gpu->error().empty()) throw Error("device='cuda': " + gpu->error());
  py::array_t<float> image = to_numpy(job.image());
  if (aovs.empty()) return image;

  AovImages planes;
  {
    py::gil_scoped_release release;
    planes = render_aovs(rs, threads);
  }
  py::dict out;
  for (const std::string& a : aovs) {
    if (a == "depth") out["depth"] = to_numpy(planes.depth, 1);
    if (a == "normal") out["normal"] = to_numpy(planes.normal);
    if (a == "albedo") out["albedo"] = to_numpy(planes.albedo);
    if (a == "id") out["id"] = to_numpy(planes.id, 1);
  }
  return py::make_tuple(image, out);
}

}  // namespace

void bind_render(py::module_& m) {
  m.def(
      "render",
      [](Scene& scene, std::optional<int> width, std::optional<int> height, std::optional<int> spp,
         std::optional<std::string> sampler, std::optional<std::uint64_t> seed, std::optional<std::string> filter,
         std::optional<double> filter_radius, std::optional<int> adaptive_min, std::optional<double> adaptive_threshold,
         std::optional<int> max_depth, std::optional<int> supersample, std::optional<std::string> accel, int threads,
         int tile_size, double time_limit, const py::object& progress, const std::vector<std::string>& aovs,
         const std::string& device, std::optional<std::string> integrator) {
        Overrides o{width, height, spp, max_depth, supersample, adaptive_min, sampler, filter, accel, seed,
                    filter_radius, adaptive_threshold, time_limit, integrator};
        return render(scene, o, threads, tile_size, progress, aovs, device);
      },
      py::arg("scene"), py::kw_only(), py::arg("width") = py::none(), py::arg("height") = py::none(),
      py::arg("spp") = py::none(), py::arg("sampler") = py::none(), py::arg("seed") = py::none(),
      py::arg("filter") = py::none(), py::arg("filter_radius") = py::none(), py::arg("adaptive_min") = py::none(),
      py::arg("adaptive_threshold") = py::none(), py::arg("max_depth") = py::none(),
      py::arg("supersample") = py::none(), py::arg("accel") = py::none(), py::arg("threads") = 0,
      py::arg("tile_size") = 32, py::arg("time_limit") = 0.0, py::arg("progress") = py::none(),
      py::arg("aovs") = std::vector<std::string>{}, py::arg("device") = "cpu", py::arg("integrator") = py::none(),
      "The compiled part of strahl.render (see its docstring).");

  m.def(
      "explain",
      [](Scene& scene, int x, int y, int sample, std::optional<int> width, std::optional<int> height,
         std::optional<int> spp, std::optional<std::string> sampler, std::optional<std::uint64_t> seed,
         std::optional<int> max_depth, std::optional<int> supersample) {
        Overrides o;
        o.width = width;
        o.height = height;
        o.spp = spp;
        o.sampler = sampler;
        o.seed = seed;
        o.max_depth = max_depth;
        o.supersample = supersample;
        const RenderScene rs = compile_with(scene, o);
        const int samples = effective_spp(rs.sampling.sampler, rs.sampling.spp);
        if (sample < 0 || sample >= samples)
          throw Error("sample " + std::to_string(sample) + " of a pixel of " + std::to_string(samples) +
                      " samples (0 to " + std::to_string(samples - 1) + ")");
        return explain_pixel(rs, x, y, std::uint32_t(sample)).text;
      },
      py::arg("scene"), py::arg("x"), py::arg("y"), py::arg("sample") = 0, py::kw_only(), py::arg("width") = py::none(),
      py::arg("height") = py::none(), py::arg("spp") = py::none(), py::arg("sampler") = py::none(),
      py::arg("seed") = py::none(), py::arg("max_depth") = py::none(), py::arg("supersample") = py::none(),
      "The compiled part of strahl.explain (see its docstring).");
  m.def(
      "write",
      [](const py::object& array, const std::filesystem::path& path, bool linear) {
        const Image image = from_numpy(array);
        py::gil_scoped_release release;
        write_image(image, path, {linear});
      },
      py::arg("image"), py::arg("path"), py::kw_only(), py::arg("linear") = false,
      "Writes an image (height × width × 3 or height × width, linear RGB) by its extension: .png .jpg .ppm (8-bit "
      "sRGB, or linear values with linear=True), .pfm .exr (float). Through a temporary file and a rename.");
  m.def(
      "read",
      [](const std::filesystem::path& path) {
        Image image;
        {
          py::gil_scoped_release release;
          image = read_image(path);
        }
        return to_numpy(image);
      },
      py::arg("path"), "Reads .png .jpg .ppm .pfm .exr into a height × width × 3 float32 array (8-bit values / 255).");
  m.def("version", [] { return std::string(version()); }, "The linked library's version, e.g. '0.1.0'.");
  m.attr("__version__") = STRAHL_VERSION_STRING;
  m.def(
      "_scene_hash",
      [](Scene& scene) {
        const RenderScene rs = compile(scene);
        return scene_hash(rs);
      },
      py::arg("scene"), "The fingerprint of the compiled scene (render/scene_hash.h), for tests.");
}

}  // namespace strahl::python
