// The interactive viewer (viewer.h): its window, the loop that looks at the input at least every
// 4 ms, hands the render thread a new request when the camera or a setting changed, and shows the
// newest image with its HUD. The input itself: viewer_input.cpp.

#include "viewer.h"

#include <SDL.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "camera_yaml.h"
#include "console.h"
#include "interrupt.h"
#include "keys.h"
#include "strahl/scene/camera_build.h"
#include "text.h"
#include "viewer_window.h"

namespace strahl::view {


namespace {

bool same_camera(const CameraDescription& a, const CameraDescription& b) {
  return a.position == b.position && a.look_at == b.look_at && a.up == b.up && a.fov_degrees == b.fov_degrees &&
         a.fov_axis == b.fov_axis && a.explicit_image_plane == b.explicit_image_plane && a.l == b.l && a.r == b.r &&
         a.b == b.b && a.t == b.t && a.d == b.d && a.aperture == b.aperture && a.focus_distance == b.focus_distance &&
         a.has_focus_point == b.has_focus_point && a.focus_point == b.focus_point &&
         a.shutter_open == b.shutter_open && a.shutter_close == b.shutter_close;
}

bool same_sampling(const SamplingSettings& a, const SamplingSettings& b) {
  return a.sampler == b.sampler && a.spp == b.spp && a.seed == b.seed && a.filter.kind == b.filter.kind &&
         a.filter.radius == b.filter.radius && a.adaptive_min == b.adaptive_min &&
         a.adaptive_threshold == b.adaptive_threshold;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    out.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

// Long messages (an error with a path) folded to the window's width.
std::vector<std::string> wrap(const std::string& text, std::size_t width) {
  std::vector<std::string> out;
  for (std::string line : lines_of(text)) {
    while (line.size() > width) {
      std::size_t cut = line.rfind(' ', width);
      if (cut == std::string::npos || cut < width / 2) cut = width;
      out.push_back(line.substr(0, cut));
      line = line.substr(cut == width ? cut : cut + 1);
    }
    out.push_back(line);
  }
  return out;
}

}  // namespace

void Viewer::adopt(LoadedScene s, bool first) {
  const RenderScene& rs = *s.render;
  // The file's values replace the viewer's where the file changed them; the viewer's own
  // changes (the camera moved, a key pressed) stay where it did not.
  if (first || !same_camera(s.camera, file_camera_)) settings_.camera = settings_.home = s.camera;
  if (first || rs.settings.max_depth != file_max_depth_) settings_.max_depth = rs.settings.max_depth;
  if (first || rs.settings.integrator != file_integrator_) settings_.integrator = rs.settings.integrator;
  if (first || !same_sampling(rs.sampling, file_sampling_)) settings_.sampling = rs.sampling;
  if (first || rs.camera.nx != file_width_ || rs.camera.ny != file_height_) {
    settings_.width = rs.camera.nx;
    settings_.height = rs.camera.ny;
    if (window_) SDL_SetWindowSize(window_, settings_.width, settings_.height);
  }
  file_camera_ = s.camera;
  file_max_depth_ = rs.settings.max_depth;
  file_integrator_ = rs.settings.integrator;
  file_sampling_ = rs.sampling;
  file_width_ = rs.camera.nx;
  file_height_ = rs.camera.ny;
  settings_.accel = s.accel;
  // A later scene to the GPU (the first is there already); the window waits for the upload.
  if (!first)
    if (const std::string why = backend_.use_scene(s.render); !why.empty()) message(why);
  scene_ = std::move(s.render);
  if (!s.files.empty()) watch_.watch(s.files);
  error_.clear();
  dirty_ = true;
}

void Viewer::open_window() {
  int w = settings_.width, h = settings_.height;
  SDL_Rect usable{};
  if (SDL_GetDisplayUsableBounds(0, &usable) == 0 && usable.w > 0 && usable.h > 0) {
    // A window larger than the screen shows the image scaled down.
    const double fit = std::min({1.0, double(usable.w) / w, double(usable.h) / h});
    w = std::max(1, int(w * fit));
    h = std::max(1, int(h * fit));
  }
  const std::string title = "strahl-view - " + (options_.scene.empty() ? std::string("lecture scene") : options_.scene);
  window_ = SDL_CreateWindow(title.c_str(), SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, w, h,
                             SDL_WINDOW_RESIZABLE | SDL_WINDOW_SHOWN);
  if (!window_) throw Error(std::string("cannot open a window: ") + SDL_GetError());
  sdl_renderer_ = SDL_CreateRenderer(window_, -1, 0);
  if (!sdl_renderer_) sdl_renderer_ = SDL_CreateRenderer(window_, -1, SDL_RENDERER_SOFTWARE);
  if (!sdl_renderer_) throw Error(std::string("cannot draw into the window: ") + SDL_GetError());
}

SDL_Rect Viewer::image_rect() const {
  int ww = 1, wh = 1;
  SDL_GetRendererOutputSize(sdl_renderer_, &ww, &wh);
  // The image's aspect ratio (the full resolution's), as large as the window allows.
  const double fit = std::min(double(ww) / settings_.width, double(wh) / settings_.height);
  const int w = std::max(1, int(std::lround(settings_.width * fit))), h = std::max(1, int(std::lround(settings_.height * fit)));
  return SDL_Rect{(ww - w) / 2, (wh - h) / 2, w, h};
}

void Viewer::message(const std::string& text, bool error) {
  if (error) {
    error_ = text;
    console::err("strahl-view: error: {}\n", text);
  } else {
    note_ = text;
    note_time_ = Clock::now();
    if (!options_.quiet) console::out("{}\n", text);
  }
  redraw_ = true;
}

void Viewer::submit() {
  if (!scene_) return;
  FrameRequest r;
  r.scene = scene_;
  r.camera = settings_.camera;
  r.width = settings_.width;
  r.height = settings_.height;
  r.max_depth = settings_.max_depth;
  r.integrator = settings_.integrator;
  r.sampling = settings_.sampling;
  r.unlimited = settings_.unlimited;
  r.time_limit = options_.time_limit;
  r.display = settings_.display;
  r.scale = view_.scale;
  submitted_ = renderer_.submit(std::move(r));
  dirty_ = false;
  redraw_ = true;
}

void Viewer::refresh_image() {
  FrameStatus s;
  Image image;
  const bool again = renderer_reshow_;
  renderer_reshow_ = false;
  if (renderer_.take_image(image, s)) {
    frame_ = std::move(image);
  } else if (again && frame_.width() > 0) {
    s = renderer_.status();
  } else {
    return;
  }
  frame_status_ = s;
  to_display(frame_, s.display, settings_.exposure, rgba_);
  if (!image_texture_ || texture_w_ != rgba_.width || texture_h_ != rgba_.height) {
    if (image_texture_) SDL_DestroyTexture(image_texture_);
    image_texture_ = SDL_CreateTexture(sdl_renderer_, SDL_PIXELFORMAT_RGBA32, SDL_TEXTUREACCESS_STREAMING, rgba_.width, rgba_.height);
    texture_w_ = rgba_.width;
    texture_h_ = rgba_.height;
  }
  if (image_texture_) SDL_UpdateTexture(image_texture_, nullptr, rgba_.bytes.data(), rgba_.width * 4);
  frame_times_.push_back(Clock::now());
  redraw_ = true;
}

std::vector<std::string> Viewer::hud_lines(const FrameStatus& s) {
  const Clock::time_point now = Clock::now();
  while (!frame_times_.empty() && seconds_between(frame_times_.front(), now) > 1) frame_times_.pop_front();
  std::vector<std::string> l;
  const double mrays = s.seconds > 0 ? double(s.rays.total()) / s.seconds * 1e-6 : 0;
  while (!turn_times_.empty() && seconds_between(turn_times_.front(), now) > 1) turn_times_.pop_front();
  l.push_back(fmt::format("{} frames/s  {:.1f} Mrays/s  input {} Hz", frame_times_.size(), mrays, turn_times_.size()));
  if (s.interactive)
    l.push_back(fmt::format("moving: {}x{} (1/{}), 1 spp", s.width, s.height, s.scale));
  else
    l.push_back(fmt::format("{}x{}  spp {:.4g} / {}{}", s.width, s.height, s.spp,
                            settings_.unlimited ? std::string("unlimited") : std::to_string(s.target_spp),
                            s.finished ? "  done" : ""));
  l.push_back(fmt::format("{}  depth {}  sampler {}  spp {}  accel {}", integrator_name(settings_.integrator),
                          settings_.max_depth, sampler_name(settings_.sampling.sampler), settings_.sampling.spp, accel_name(settings_.accel)));
  l.push_back(fmt::format("show {}  exposure {:+.1f}  (H: help)", display_name(settings_.display), settings_.exposure));
  l.push_back("device " + backend_.device_name());
  for (const std::string& c : lines_of(camera_yaml(settings_.camera))) l.push_back(c);
  return l;
}

void Viewer::draw() {
  SDL_SetRenderDrawColor(sdl_renderer_, 0, 0, 0, 255);
  SDL_RenderClear(sdl_renderer_);
  const SDL_Rect rect = image_rect();
  if (image_texture_) SDL_RenderCopy(sdl_renderer_, image_texture_, nullptr, &rect);

  int ww = 1, wh = 1;
  SDL_GetRendererOutputSize(sdl_renderer_, &ww, &wh);
  const std::size_t columns = std::size_t(std::max(20, ww / kGlyphWidth - 4));
  std::vector<std::string> lines;
  std::vector<Rgba> colours;
  auto add = [&](const std::vector<std::string>& ls, Rgba c) {
    for (const std::string& s : ls) {
      lines.push_back(s);
      colours.push_back(c);
    }
  };
  if (settings_.help) {
    add({"strahl-view: keys and mouse", ""}, kYellow);
    for (const KeyHelp& k : kKeyHelp) add({fmt::format("{:<20} {}", k.keys, k.action)}, kWhite);
  } else if (settings_.hud) {
    add(hud_lines(frame_status_), kWhite);
  }
  if (!frame_status_.error.empty()) add(wrap("camera: " + frame_status_.error, columns), kRed);
  if (!error_.empty()) add(wrap(error_, columns), kRed);
  // Passing notes belong to the HUD; errors show always.
  if ((settings_.hud || settings_.help) && !note_.empty() && seconds_between(note_time_, Clock::now()) < 4)
    add(wrap(note_, columns), kYellow);
  if (!lines.empty()) {
    const Canvas box = text_box(lines, kWhite, 1, colours);
    if (!overlay_texture_ || overlay_w_ != box.width() || overlay_h_ != box.height()) {
      if (overlay_texture_) SDL_DestroyTexture(overlay_texture_);
      overlay_texture_ = SDL_CreateTexture(sdl_renderer_, SDL_PIXELFORMAT_RGBA32, SDL_TEXTUREACCESS_STREAMING, box.width(), box.height());
      if (overlay_texture_) SDL_SetTextureBlendMode(overlay_texture_, SDL_BLENDMODE_BLEND);
      overlay_w_ = box.width();
      overlay_h_ = box.height();
    }
    if (overlay_texture_) {
      SDL_UpdateTexture(overlay_texture_, nullptr, box.bytes().data(), box.width() * 4);
      const SDL_Rect at{8, 8, box.width(), box.height()};
      SDL_RenderCopy(sdl_renderer_, overlay_texture_, nullptr, &at);
    }
  }
  SDL_RenderPresent(sdl_renderer_);
  redraw_ = false;
  last_hud_ = Clock::now();
}

int Viewer::run(const std::atomic<bool>* interrupted) {
  open_window();
  script_last_ = Clock::now();
  const Clock::time_point start = Clock::now();
  Clock::time_point last = start;
  while (!quit_) {
    if (interrupted->load()) {
      exit_code_ = 130;
      break;
    }
    SDL_Event e;
    // At most 4 ms between looks at the input: well above 60 Hz, whatever the renderer does.
    if (SDL_WaitEventTimeout(&e, 4)) {
      handle(e);
      while (!quit_ && SDL_PollEvent(&e)) handle(e);
    }
    const Clock::time_point now = Clock::now();
    ++turns_;
    longest_gap_ = std::max(longest_gap_, seconds_between(last, now));
    turn_times_.push_back(now);
    fly(std::min(0.1, seconds_between(last, now)));
    last = now;
    poll_files();
    if (dirty_) submit();
    refresh_image();
    // The HUD's figures change without new images (frames/s falls): four redraws a second.
    if (redraw_ || seconds_between(last_hud_, now) > 0.25) draw();
    play_script();
  }
  if (exit_code_ == 130) console::err("strahl-view: interrupted ({})\n", cli::interrupt_signal_name());
  const double seconds = seconds_between(start, Clock::now());
  if (!script_.empty() && !options_.quiet)
    console::out("input: looked at {} times in {:.2f} s ({:.0f} Hz), longest gap {:.1f} ms\n", turns_, seconds,
                 double(turns_) / std::max(seconds, 1e-9), longest_gap_ * 1e3);
  return exit_code_;
}

int run_viewer(const cli::Options& options, const ViewOptions& view, LoadedScene first, DeviceBackend& backend,
               const std::atomic<bool>* interrupted) {
  // SDL would turn SIGINT into a quit event; the CLI's handler keeps Ctrl-C's meaning (130).
  SDL_SetHint(SDL_HINT_NO_SIGNAL_HANDLERS, "1");
  if (SDL_Init(SDL_INIT_VIDEO) != 0)
    throw Error(std::string("cannot open a window: ") + SDL_GetError() +
                " (no display? run under xvfb-run, set SDL_VIDEODRIVER=offscreen, or use --benchmark)");
  struct Quit {
    ~Quit() { SDL_Quit(); }
  } quit;
  int code = 0;
  {
    Viewer viewer(options, view, std::move(first), backend);
    code = viewer.run(interrupted);
  }
  return code;
}

}  // namespace strahl::view
