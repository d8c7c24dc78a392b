// strahl-view: the interactive viewer (docs/viewer.md). Takes every `strahl` flag; shows the
// scene through the same render job, 1 sample per pixel while the camera moves, accumulating
// to the scene's samples per pixel when it stops.
//   strahl-view [scene.yaml] [strahl flags] [--script FILE] [--benchmark N] [--exposure S] [--no-hud] [--scale N]
// Exit codes as strahl's: 0 closed, 1 usage, 2 scene, script or window error, 130 interrupted.

#include <CLI/CLI.hpp>

#include "benchmark.h"
#include "console.h"
#include "device.h"
#include "interrupt.h"
#include "options.h"
#include "scene_source.h"
#include "strahl/util/cancel.h"
#include "strahl/util/error.h"
#include "viewer.h"

int main(int argc, char** argv) {
  using namespace strahl;
  console::protect_streams();
  view::ViewOptions v;
  const cli::ParseResult parsed = cli::parse_options(argc, argv, "strahl-view", [&](CLI::App& app) {
    app.description("strahl-view — the interactive viewer: fly through a scene, refine to the final image when still. "
                    "Takes every strahl flag; keys: press H in the window, or see docs/viewer.md.");
    app.add_option("--script", v.script, "Play this file of timed input events into the window (docs/viewer.md, \"Scripts\")");
    app.add_option("--benchmark", v.benchmark, "Render N interactive frames (1 spp) headless, print frames/s and Mrays/s, exit")
        ->check(CLI::Range(1, 1000000));
    app.add_option("--exposure", v.exposure, "Display exposure in stops (default 0; saved images are not affected)")
        ->check(CLI::Range(-20.0, 20.0));
    app.add_flag("--no-hud", [&](std::int64_t) { v.hud = false; }, "Start with the HUD hidden (Tab shows it)");
    app.add_option("--scale", v.scale, "Render moving frames at 1/N of the resolution (default: adapt to 30 frames/s)")
        ->check(CLI::Range(1, 16));
    cli::add_device_option(app, v.device);
  });
  if (!parsed.options) return parsed.exit_code;
  const cli::Options& o = *parsed.options;
  if (const std::string conflict = cli::device_accel_conflict(v.device, o); !conflict.empty()) {
    console::err("strahl-view: error: {}\n", conflict);
    return 1;
  }
  // Before loading: a signal while the scene loads ends the viewer with 130 (the loaders poll the flag).
  const std::atomic<bool>* interrupted = cli::install_interrupt_handlers();
  try {
    if (o.checkpoint > 0) console::err("strahl-view: --checkpoint has no effect in the viewer (Ctrl+S saves)\n");
    view::LoadedScene scene = view::load_scene_now(o);
    // The GPU for the first scene, as strahl opens it: --device cuda without one ends here.
    cli::OpenedDevice opened = cli::open_device(v.device, *scene.render);
    if (!opened.error.empty()) {
      console::err("strahl-view: error: {}\n", opened.error);
      return 2;
    }
    if (!opened.note.empty()) console::err("strahl-view: {}\n", opened.note);
    view::DeviceBackend backend(opened.gpu ? v.device : "cpu", o.threads);  // auto without a GPU: the CPU throughout
    backend.adopt_gpu(scene.render, std::move(opened.gpu));
    if (v.benchmark > 0)
      return view::run_benchmark(scene, o.scene.empty() ? "the lecture scene" : o.scene, v.benchmark, backend,
                                 o.threads, o.tile_size, interrupted);
    return view::run_viewer(o, v, std::move(scene), backend, interrupted);
  } catch (const Cancelled&) {
    console::err("strahl-view: interrupted while loading the scene\n");
    return 130;
  } catch (const std::exception& e) {
    console::err("strahl-view: error: {}\n", e.what());
    return 2;
  }
}
