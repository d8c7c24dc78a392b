// strahl: load a scene (or the lecture's), compile, render on all cores, write the image.
// Exit codes: 0 ok, 1 usage, 2 scene or I/O error.

#include <fmt/core.h>
#include <tbb/info.h>

#include <chrono>
#include <filesystem>

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
  if (!is_supported_image_extension(output))
    throw Error(output + ": unknown image format (use .png, .jpg/.jpeg, .ppm, .pfm or .exr)");

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

  cli::Progress progress(!o.quiet);
  RenderStats stats;
  const Image image = render(render_scene, {o.threads, o.tile_size}, &stats,
                             [&](long done, long total) { progress.update(done, total); });
  progress.finish();
  timings.render = stats.seconds;

  t = std::chrono::steady_clock::now();
  write_image(image, output, {o.linear});
  timings.write = seconds_since(t);

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
