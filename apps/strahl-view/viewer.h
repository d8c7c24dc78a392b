#pragma once
// The window: SDL2 events → camera and settings → ViewRenderer requests; the renderer's frame
// → a texture, with the HUD and help overlay on top; live reload; scripts (script.h).
// Everything here runs on the window's thread, which never waits for rendering.

#include <atomic>
#include <string>

#include "device_backend.h"
#include "options.h"
#include "scene_source.h"

namespace strahl::view {

struct ViewOptions {
  std::string script;     // --script FILE
  int benchmark = 0;      // --benchmark N
  double exposure = 0;    // --exposure STOPS
  bool hud = true;        // --no-hud
  int scale = 0;          // --scale N: interactive frames at 1/N resolution (0: adapt)
  std::string device = "cpu";  // --device cpu|cuda|auto
  double reload_poll = 0.2;  // seconds between looks at the scene's files
};

// Opens the window and runs until it is closed (0), `interrupted` is set (Ctrl-C: 130), or a
// script fails (2). `backend` renders the frames (it holds the first scene already when it is the GPU's).
int run_viewer(const cli::Options& options, const ViewOptions& view, LoadedScene first, DeviceBackend& backend,
               const std::atomic<bool>* interrupted);

}  // namespace strahl::view
