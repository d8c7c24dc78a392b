// strahl: load a scene (or the lecture's), compile, render on all cores (or the GPU: --device),
// write the image.
// Exit codes: 0 ok, 1 usage, 2 scene or I/O error, 130 interrupted (SIGINT/SIGTERM/SIGHUP; the
// image rendered so far is written, or nothing when the signal came before rendering).

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/info.h>

#include <CLI/CLI.hpp>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <vector>

#include "console.h"
#include "device.h"
#include "interrupt.h"
#include "options.h"
#include "outputs.h"
#include "progress.h"
#include "setup.h"
#include "strahl/cuda/cuda_backend.h"
#include "strahl/image/image_io.h"
#include "strahl/render/cpu_backend.h"
#include "strahl/render/explain.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/renderer.h"
#include "strahl/sampling/pixel_sampler.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/solids.h"
#include "strahl/util/cancel.h"
#include "summary.h"

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// --device (docs/cli.md, docs/gpu.md): the back end the render job runs on.
std::string device = "cpu";
// --explain X,Y[,S] (docs/cli.md): sample S of pixel (X, Y) explained instead of rendering.
std::vector<int> explain;

// Prints the ray tree of the sample --explain names (render/explain.h); no image is written.
int explain_sample(const strahl::cli::Options& o) {
  using namespace strahl;
  const RenderScene render_scene = compile(cli::configured_scene(o));
  for (const std::string& w : render_scene.warnings) strahl::console::err("strahl: warning: {}\n", w);
  const int nx = render_scene.camera.nx, ny = render_scene.camera.ny;
  const int spp = effective_spp(render_scene.sampling.sampler, render_scene.sampling.spp);
  const int sample = explain.size() > 2 ? explain[2] : 0;
  if (const std::string why = explain_refusal(render_scene.view()); !why.empty()) {
    strahl::console::err("strahl: error: --{} (add --integrator whitted to explain the Whitted image)\n", why);
    return 1;
  }
  if (explain[0] >= nx || explain[1] >= ny || sample >= spp) {
    strahl::console::err("strahl: error: --explain {}: the image has {}×{} pixels (x 0 to {}, y 0 to {} from the top) and "
                         "{} samples per pixel (0 to {})\n",
                         fmt::join(explain, ","), nx, ny, nx - 1, ny - 1, spp, spp - 1);
    return 1;
  }
  strahl::console::out("{}", explain_pixel(render_scene, explain[0], explain[1], std::uint32_t(sample)).text);
  return 0;
}

int run(const strahl::cli::Options& o) {
  using namespace strahl;
  namespace fs = std::filesystem;
  cli::Timings timings;
  const std::string output = cli::output_path(o);
  // Before any work: a run that could not write its image or an AOV fails at once.
  cli::check_outputs(o, output);
  const std::atomic<bool>* cancel = cli::install_interrupt_handlers();

  auto t = std::chrono::steady_clock::now();
  const Scene scene = cli::configured_scene(o);
  timings.load = seconds_since(t);

  t = std::chrono::steady_clock::now();
  const RenderScene render_scene = compile(scene);
  timings.build = seconds_since(t);
  for (const std::string& w : render_scene.warnings) strahl::console::err("strahl: warning: {}\n", w);
  check_image_size(output, render_scene.camera.nx, render_scene.camera.ny);  // a JPEG of width 65536

  if (cancel->load()) throw Cancelled();  // interrupted while building: nothing rendered, nothing written
  // The GPU when asked for and usable; `auto` falls back to the CPU and says so.
  cli::OpenedDevice opened = cli::open_device(device, render_scene);
  if (!opened.error.empty()) {
    strahl::console::err("strahl: error: {}\n", opened.error);
    return 2;
  }
  if (!opened.note.empty()) strahl::console::err("strahl: {}\n", opened.note);
  const std::unique_ptr<CudaBackend> gpu = std::move(opened.gpu);
  cli::Progress progress(!o.quiet);
  // render() (render/renderer.h) on the back end chosen.
  JobOptions job_options;
  job_options.tile_size = o.tile_size;
  job_options.cancel = cancel;
  job_options.time_limit = o.time_limit;
  if (o.checkpoint > 0) {
    job_options.checkpoint_interval = o.checkpoint;
    job_options.checkpoint = [&](const Image& partial) { write_image(partial, output, {o.linear}); };
  }
  job_options.progress = [&](long done, long total) {
    cli::hold_for_test("render");
    progress.update(done, total);
  };
  RenderJob job(render_scene.view(), render_scene.sampling, std::move(job_options));
  if (gpu) {
    job.run(*gpu);
  } else {
    CpuBackend cpu(o.threads);
    job.run(cpu);
  }
  const RenderStats stats = job.stats();
  if (gpu && !gpu->error().empty()) {  // the GPU failed mid-render: nothing written
    strahl::console::err("strahl: error: --device cuda: {}\n", gpu->error());
    return 2;
  }
  const Image image = job.image();
  if (!stats.cancelled) progress.finish();
  timings.render = stats.seconds;

  t = std::chrono::steady_clock::now();
  cli::hold_for_test("write");
  write_image(image, output, {o.linear});
  if (!o.aov.empty()) cli::write_aovs(render_scene, o, output);
  timings.write = seconds_since(t);
  if (cancel->load()) {
    strahl::console::err("strahl: interrupted ({}); wrote the image rendered so far to {}\n",
                         cli::interrupt_signal_name(), output);
    return 130;
  }

  // POV-Ray's isosurface warning: the gradient met, and the max_gradient to use instead.
  for (const std::string& w : implicit_warnings(render_scene)) strahl::console::err("strahl: warning: {}\n", w);
  if (!o.quiet) {
    const int threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
    strahl::console::out("{}", cli::summary(output, image.width(), image.height(), threads, timings,
                                  stats, render_scene));
    strahl::console::out("{}", cli::device_line(gpu.get(), stats, threads));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  strahl::console::protect_streams();  // docs/cli.md, "Streams and signals"
  const strahl::cli::ParseResult parsed = strahl::cli::parse_options(argc, argv, "strahl", [](CLI::App& app) {
    strahl::cli::add_device_option(app, device);
    app.add_option("--explain", explain,
                   "Print the ray tree of one camera sample instead of rendering: X,Y (the pixel, from the top left) "
                   "or X,Y,S (its sample S, default 0)")
        ->expected(2, 3)
        ->delimiter(',')
        ->check(CLI::NonNegativeNumber);
  });
  if (!parsed.options) return parsed.exit_code;
  // The GPU traverses the BVH (or the naive loop) only.
  if (const std::string conflict = strahl::cli::device_accel_conflict(device, *parsed.options); !conflict.empty()) {
    strahl::console::err("strahl: error: {}\n", conflict);
    return 1;
  }
  try {
    if (!explain.empty()) {
      // The explanation is the CPU's walk of the ray tree; a GPU computes the same numbers.
      if (device != "cpu") strahl::console::err("strahl: note: --explain traces on the CPU (--device {} is not used)\n", device);
      return explain_sample(*parsed.options);
    }
    return run(*parsed.options);
  } catch (const strahl::Cancelled&) {  // a signal while loading or building
    strahl::console::err("strahl: interrupted ({}) before rendering; nothing written\n",
                         strahl::cli::interrupt_signal_name());
    return 130;
  } catch (const strahl::Error& e) {
    strahl::console::err("strahl: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    strahl::console::err("strahl: error: {}\n", e.what());
    return 2;
  }
}
