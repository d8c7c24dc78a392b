// strahl: load a scene (or the lecture's), compile, render on all cores, write the image.
// Exit codes: 0 ok, 1 usage, 2 scene or I/O error, 130 interrupted (SIGINT/SIGTERM; the image
// rendered so far is written).

#include <tbb/info.h>

#include <chrono>
#include <csignal>
#include <filesystem>

#include "console.h"
#include "interrupt.h"
#include "options.h"
#include "outputs.h"
#include "progress.h"
#include "strahl/image/image_io.h"
#include "strahl/render/aov.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene_file.h"
#include "summary.h"

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Command-line sampling settings over the scene's. A time limit without a sample count renders
// until the limit (up to 65536 samples per pixel).
void apply_sampling_options(const strahl::cli::Options& o, strahl::SamplingSettings& s) {
  using namespace strahl;
  if (o.sampler) s.sampler = *sampler_from_name(*o.sampler);
  if (o.spp) s.spp = *o.spp;
  if (o.seed) s.seed = *o.seed;
  if (o.filter) s.filter.kind = *filter_from_name(*o.filter);
  if (o.filter_radius) s.filter.radius = *o.filter_radius;
  if (o.adaptive_min) s.adaptive_min = *o.adaptive_min;
  if (o.adaptive_threshold) s.adaptive_threshold = *o.adaptive_threshold;
  if (o.time_limit > 0 && !o.spp && s.spp == 0) s.spp = 65536;
}

// <output stem>.<name>.exr beside the image, for each AOV asked for.
void write_aovs(const strahl::RenderScene& scene, const strahl::cli::Options& o, const std::string& output) {
  using namespace strahl;
  const AovImages aovs = render_aovs(scene, o.threads);
  for (const std::string& name : o.aov) {
    const Image& img = name == "depth" ? aovs.depth : name == "normal" ? aovs.normal : name == "albedo" ? aovs.albedo : aovs.id;
    write_image(img, cli::aov_path(output, name));
  }
}

int run(const strahl::cli::Options& o) {
  using namespace strahl;
  namespace fs = std::filesystem;
  cli::Timings timings;
  const std::string output =
      !o.output.empty() ? o.output : (o.scene.empty() ? "lecture" : fs::path(o.scene).stem().string()) + ".png";
  // Before any work: a run that could not write its image or an AOV fails at once.
  cli::check_outputs(o, output);
  const std::atomic<bool>* cancel = cli::install_interrupt_handlers();

  auto t = std::chrono::steady_clock::now();
  Scene scene = o.scene.empty() ? lecture_scene() : load_scene(o.scene);
  if (o.width) scene.settings.width = *o.width;
  if (o.height) scene.settings.height = *o.height;
  if (o.max_depth) scene.settings.max_depth = *o.max_depth;
  if (o.supersample) scene.settings.supersample = *o.supersample;
  if (o.accel) scene.settings.accel = *accel_from_name(*o.accel);
  apply_sampling_options(o, scene.settings.sampling);
  timings.load = seconds_since(t);

  t = std::chrono::steady_clock::now();
  const RenderScene render_scene = compile(scene);
  timings.build = seconds_since(t);
  check_image_size(output, render_scene.camera.nx, render_scene.camera.ny);  // a JPEG of width 65536

  if (cancel->load()) {  // interrupted while loading: nothing rendered, nothing written
    strahl::console::err("strahl: interrupted before rendering; nothing written\n");
    return 130;
  }
  cli::Progress progress(!o.quiet);
  RenderStats stats;
  RenderOptions render_options;
  render_options.threads = o.threads;
  render_options.tile_size = o.tile_size;
  render_options.time_limit = o.time_limit;
  if (o.checkpoint > 0) {
    render_options.checkpoint_interval = o.checkpoint;
    render_options.checkpoint = [&](const Image& partial) { write_image(partial, output, {o.linear}); };
  }
  render_options.cancel = cancel;
  const Image image = render(render_scene, render_options, &stats,
                             [&](long done, long total) { progress.update(done, total); });
  if (!stats.cancelled) progress.finish();
  timings.render = stats.seconds;

  t = std::chrono::steady_clock::now();
  write_image(image, output, {o.linear});
  if (!o.aov.empty()) write_aovs(render_scene, o, output);
  timings.write = seconds_since(t);
  if (cancel->load()) {
    strahl::console::err("strahl: interrupted ({}); wrote the image rendered so far to {}\n",
               cli::interrupt_signal() == SIGTERM ? "SIGTERM" : "SIGINT", output);
    return 130;
  }

  if (!o.quiet) {
    const int threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
    strahl::console::out("{}", cli::summary(output, image.width(), image.height(), threads, timings,
                                  stats, render_scene));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  strahl::console::protect_streams();  // docs/cli.md, "Streams and signals"
  const strahl::cli::ParseResult parsed = strahl::cli::parse_options(argc, argv);
  if (!parsed.options) return parsed.exit_code;
  try {
    return run(*parsed.options);
  } catch (const strahl::Error& e) {
    strahl::console::err("strahl: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    strahl::console::err("strahl: error: {}\n", e.what());
    return 2;
  }
}
