#include "benchmark.h"

#include <sys/resource.h>
#include <tbb/info.h>

#include <fmt/format.h>

#include <chrono>

#include "camera_control.h"
#include "console.h"
#include "view_renderer.h"

namespace strahl::view {

namespace {
// CPU seconds this process has used (all threads, user and system).
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}
}  // namespace

int run_benchmark(const LoadedScene& scene, const std::string& name, int frames, DeviceBackend& backend, int threads,
                  int tile_size, const std::atomic<bool>* interrupted) {
  using Clock = std::chrono::steady_clock;
  ViewRenderer renderer(backend, threads, tile_size);
  const RenderScene& rs = *scene.render;
  FrameRequest request;
  request.scene = scene.render;
  request.camera = scene.camera;
  request.width = rs.camera.nx;
  request.height = rs.camera.ny;
  request.max_depth = rs.settings.max_depth;
  request.integrator = rs.settings.integrator;
  request.sampling = rs.sampling;

  constexpr int kWarmUp = 2;
  RayCounters rays;
  double render_seconds = 0;
  Clock::time_point start{};
  double cpu_start = 0;
  for (int i = -kWarmUp; i < frames; ++i) {
    if (i == 0) {
      start = Clock::now();
      cpu_start = cpu_seconds();
    }
    if (interrupted && interrupted->load()) {
      console::err("strahl-view: interrupted\n");
      return 130;
    }
    orbit(request.camera, 0.005, 0);  // a small drag between frames
    const FrameStatus s = renderer.render_interactive(request, 1);
    if (!s.error.empty()) {
      console::err("strahl-view: error: {}\n", s.error);
      return 2;
    }
    if (const std::string failure = backend.take_failure(); !failure.empty()) {
      console::err("strahl-view: error: {}\n", failure);
      return 2;
    }
    if (i >= 0) {
      rays += s.rays;
      render_seconds += s.seconds;
    }
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const double cpu_used = cpu_seconds() - cpu_start;
  const int used = threads > 0 ? threads : tbb::info::default_concurrency();
  const std::string device = backend.device_name();
  console::out("strahl-view benchmark: {} at {}x{}, 1 spp per frame, max depth {}, accel {}, {}\n", name,
               request.width, request.height, request.max_depth, accel_name(scene.accel),
               device == "cpu" ? fmt::format("{} threads", used) : device);
  console::out("frames {} in {:.3f} s: {:.1f} frames/s, {:.1f} Mrays/s ({:.2f} Mrays per frame: camera {:.2f}, shadow {:.2f}, "
               "reflection {:.2f}, refraction {:.2f})\n",
               frames, seconds, frames / seconds, double(rays.total()) / seconds * 1e-6,
               double(rays.total()) / frames * 1e-6, double(rays.camera) / frames * 1e-6,
               double(rays.shadow) / frames * 1e-6, double(rays.reflection) / frames * 1e-6,
               double(rays.refraction) / frames * 1e-6);
  console::out("render time {:.3f} s of {:.3f} s ({:.1f}%: the rest is setting up each frame's job)\n", render_seconds,
               seconds, 100 * render_seconds / seconds);
  // On a shared machine the wall-clock figures depend on the load; CPU time does much less.
  console::out("cpu time {:.3f} s ({:.2f} of {} threads busy on average): {:.1f} frames per CPU second\n", cpu_used,
               cpu_used / seconds, used, frames / cpu_used);
  return 0;
}

}  // namespace strahl::view
