// strahl: load a scene (or the lecture's), compile, render on all cores, write the image.
// Exit codes: 0 ok, 1 usage, 2 scene or I/O error, 130 interrupted (SIGINT/SIGTERM; the image
// rendered so far is written).

#include <fmt/core.h>
#include <tbb/info.h>

#include <chrono>
#include <csignal>
#include <filesystem>

#include "interrupt.h"
#include "options.h"
#include "progress.h"
#include "strahl/image/image_io.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene_file.h"
#include "summary.h"

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

int run(const strahl::cli::Options& o) {
  using namespace strahl;
  namespace fs = std::filesystem;
  cli::Timings timings;
  const std::string output =
      !o.output.empty() ? o.output : (o.scene.empty() ? "lecture" : fs::path(o.scene).stem().string()) + ".png";
  // Before any work: a run that could not write its image fails at once.
  check_output_path(output);
  const std::atomic<bool>* cancel = cli::install_interrupt_handlers();

  auto t = std::chrono::steady_clock::now();
  Scene scene = o.scene.empty() ? lecture_scene() : load_scene(o.scene);
  if (o.width) scene.settings.width = *o.width;
  if (o.height) scene.settings.height = *o.height;
  if (o.max_depth) scene.settings.max_depth = *o.max_depth;
  if (o.supersample) scene.settings.supersample = *o.supersample;
  if (o.accel) scene.settings.accel = *accel_from_name(*o.accel);
  timings.load = seconds_since(t);

  t = std::chrono::steady_clock::now();
  const RenderScene render_scene = compile(scene);
  timings.build = seconds_since(t);

  if (cancel->load()) {  // interrupted while loading: nothing rendered, nothing written
    fmt::print(stderr, "strahl: interrupted before rendering; nothing written\n");
    return 130;
  }
  cli::Progress progress(!o.quiet);
  RenderStats stats;
  RenderOptions render_options{o.threads, o.tile_size};
  render_options.cancel = cancel;
  const Image image = render(render_scene, render_options, &stats,
                             [&](long done, long total) { progress.update(done, total); });
  if (!stats.cancelled) progress.finish();
  timings.render = stats.seconds;

  t = std::chrono::steady_clock::now();
  write_image(image, output, {o.linear});
  timings.write = seconds_since(t);
  if (cancel->load()) {
    fmt::print(stderr, "strahl: interrupted ({}); wrote the image rendered so far to {}\n",
               cli::interrupt_signal() == SIGTERM ? "SIGTERM" : "SIGINT", output);
    return 130;
  }

  if (!o.quiet) {
    const int threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
    fmt::print("{}", cli::summary(output, image.width(), image.height(), render_scene.supersample, threads, timings,
                                  stats, render_scene));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const strahl::cli::ParseResult parsed = strahl::cli::parse_options(argc, argv);
  if (!parsed.options) return parsed.exit_code;
  try {
    return run(*parsed.options);
  } catch (const strahl::Error& e) {
    fmt::print(stderr, "strahl: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "strahl: error: {}\n", e.what());
    return 2;
  }
}
