// strahl-gpu-bench: the CUDA back end's speed with the scene resident on the GPU (docs/gpu.md).
// Takes strahl's scene options (scene file, --width, --height, --spp, --sampler, …) and
//   --frames N   renders the image N times (after one warm-up frame), each a whole render job
//                on the GPU, and reports the median kernel time per frame as frames/s;
//   --primary    also times one camera ray per pixel (nearest hit only) and reports Grays/s;
//   --kernels    also times every variant of the render kernel this build holds (CMake's
//                STRAHL_CUDA_KERNEL_MIN_BLOCKS: registers fitted for 1, 3, 4 … blocks per SM) the
//                same way, one "kernel" line each;
//   --viewer N   also renders N of the viewer's interactive frames on the GPU (strahl-view
//                --benchmark N --device cuda, without a window): frames/s with every frame's job
//                set-up, copies and film merge, as the viewer shows them.
// Kernel times are CUDA events around the launches: uploads, the film's copies and the host's
// packing of tiles are not in them (they are reported apart, as wall time per frame).
// Exit codes: 0 ok, 1 usage, 2 no usable GPU or a scene error.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include <CLI/CLI.hpp>

#include "benchmark.h"
#include "console.h"
#include "device_backend.h"
#include "options.h"
#include "scene_source.h"
#include "setup.h"
#include "strahl/cuda/cuda_backend.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/scene.h"

namespace {

int frames = 20;
bool primary = false;
bool all_kernels = false;
int viewer_frames = 0;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

struct Timed {
  double kernel = 0, wall = 0;  // median seconds per frame
  strahl::RayCounters rays;     // of one frame
};

// `frames` whole render jobs on the GPU after one warm-up; false when one failed (the reason printed).
bool time_frames(const strahl::RenderScene& scene, const strahl::cli::Options& o, strahl::CudaBackend& gpu, Timed& t) {
  using namespace strahl;
  std::vector<double> kernel, wall;
  for (int f = -1; f < frames; ++f) {  // frame −1: warm-up
    JobOptions jo;
    jo.tile_size = o.tile_size;
    RenderJob job(scene.view(), scene.sampling, std::move(jo));
    const double before = gpu.stats().kernel_seconds;
    const auto w0 = std::chrono::steady_clock::now();
    job.run(gpu);
    const double w = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    if (!gpu.error().empty()) {
      console::err("strahl-gpu-bench: error: --device cuda: {}\n", gpu.error());
      return false;
    }
    if (f < 0) continue;
    kernel.push_back(gpu.stats().kernel_seconds - before);
    wall.push_back(w);
    t.rays = job.stats().rays;
  }
  t.kernel = median(kernel);
  t.wall = median(wall);
  return true;
}

int run(const strahl::cli::Options& o) {
  using namespace strahl;
  const RenderScene scene = compile(cli::configured_scene(o));
  std::string why;
  auto t0 = std::chrono::steady_clock::now();
  std::unique_ptr<CudaBackend> gpu = CudaBackend::create(scene, why);
  if (!gpu) {
    console::err("strahl-gpu-bench: error: --device cuda: {}\n", why);
    return 2;
  }
  const double open_upload = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const int nx = scene.camera.nx, ny = scene.camera.ny;
  const std::string name = o.scene.empty() ? "lecture" : o.scene.substr(o.scene.rfind('/') + 1);
  Timed t;
  if (!time_frames(scene, o, *gpu, t)) return 2;
  const CudaStats g = gpu->stats();
  console::out("device   {}, {:.1f} MiB used ({:.1f} MiB in use on the device), open+upload {:.3f} s (upload {:.3f} s); "
               "render kernel: {}\n",
               g.device, double(g.memory_used) / (1 << 20), double(g.memory_in_use) / (1 << 20), open_upload,
               g.upload_seconds, g.kernel);
  const auto per_second = [](double n, double seconds) { return seconds > 0 ? n / seconds : 0.0; };
  console::out("frame    {} {}x{} {} spp: kernel {:.3f} ms/frame = {:.1f} frames/s (median of {}), wall {:.3f} ms/frame, "
               "{} rays/frame = {:.3f} Grays/s\n",
               name, nx, ny, scene.sampling.spp, t.kernel * 1e3, per_second(1, t.kernel), frames, t.wall * 1e3,
               t.rays.total(), per_second(double(t.rays.total()), t.kernel) * 1e-9);
  if (all_kernels) {
    for (int k = 0; k < int(gpu->kernels().size()); ++k) {
      const CudaKernel& v = gpu->kernels()[std::size_t(k)];
      Timed tk;
      if (!gpu->use_kernel(k) || !time_frames(scene, o, *gpu, tk)) return 2;
      console::out("kernel   {} {}x{} {} spp, launch bounds {}x{} ({}): kernel {:.3f} ms/frame = {:.1f} frames/s "
                   "(median of {}), {} rays/frame = {:.3f} Grays/s\n",
                   name, nx, ny, scene.sampling.spp, v.block, v.min_blocks, describe(v), tk.kernel * 1e3,
                   per_second(1, tk.kernel), frames, tk.rays.total(),
                   per_second(double(tk.rays.total()), tk.kernel) * 1e-9);
    }
    gpu->use_kernel(0);
  }
  if (primary) {
    const double p = gpu->primary_seconds(scene.view(), frames, why);
    if (p < 0) {
      console::err("strahl-gpu-bench: error: {}\n", why);
      return 2;
    }
    console::out("primary  {} {}x{} ({} triangles): {:.3f} ms/launch = {:.3f} Grays/s (median of {})\n", name, nx, ny,
                 scene.triangles.size(), p * 1e3, p > 0 ? double(nx) * double(ny) / p * 1e-9 : 0.0, frames);
  }
  if (viewer_frames > 0) {
    gpu.reset();
    view::LoadedScene loaded = view::load_scene_now(o);
    std::unique_ptr<CudaBackend> viewer_gpu = CudaBackend::create(*loaded.render, why);
    if (!viewer_gpu) {
      console::err("strahl-gpu-bench: error: --device cuda: {}\n", why);
      return 2;
    }
    view::DeviceBackend backend("cuda", o.threads);
    backend.adopt_gpu(loaded.render, std::move(viewer_gpu));
    return view::run_benchmark(loaded, name, viewer_frames, backend, o.threads, o.tile_size, nullptr);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const strahl::cli::ParseResult parsed =
      strahl::cli::parse_options(argc, argv, "strahl-gpu-bench", [](CLI::App& app) {
        app.add_option("--frames", frames, "Timed frames after one warm-up (default 20)")->check(CLI::Range(1, 100000));
        app.add_flag("--primary", primary, "Also time primary rays (nearest hit, one per pixel): Grays/s");
        app.add_flag("--kernels", all_kernels,
                     "Also time every variant of the render kernel this build holds (CMake's STRAHL_CUDA_KERNEL_MIN_BLOCKS)");
        app.add_option("--viewer", viewer_frames, "Also render N of the viewer's interactive frames on the GPU (frames/s)")
            ->check(CLI::Range(1, 100000));
      });
  if (!parsed.options) return parsed.exit_code;
  try {
    return run(*parsed.options);
  } catch (const std::exception& e) {
    strahl::console::err("strahl-gpu-bench: error: {}\n", e.what());
    return 2;
  }
}
