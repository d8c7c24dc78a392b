#include "viewer.h"

#include <SDL.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <deque>
#include <fmt/format.h>
#include <set>

#include "camera_control.h"
#include "camera_yaml.h"
#include "console.h"
#include "display.h"
#include "interrupt.h"
#include "keys.h"
#include "save.h"
#include "script.h"
#include "setup.h"
#include "strahl/render/explain.h"
#include "strahl/render/intersect_scene.h"
#include "strahl/scene/camera_build.h"
#include "text.h"
#include "view_renderer.h"

namespace strahl::view {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_between(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

constexpr SamplerKind kSamplers[] = {SamplerKind::Grid, SamplerKind::Stratified, SamplerKind::Random, SamplerKind::Sobol,
                                     SamplerKind::Adaptive};
constexpr Display kDisplays[] = {Display::Beauty, Display::Depth, Display::Normal, Display::Albedo, Display::Id};
constexpr double kScriptWaitLimit = 300;  // seconds a script's `wait` may take
constexpr double kFlySpeed = 0.6;         // distances to look_at per second
constexpr Rgba kWhite{235, 235, 235, 255}, kRed{255, 110, 100, 255}, kYellow{255, 220, 120, 255};

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

class Viewer {
 public:
  Viewer(const cli::Options& options, const ViewOptions& view, LoadedScene first, DeviceBackend& backend)
      : options_(options),
        view_(view),
        backend_(backend),
        renderer_(backend, options.threads, options.tile_size, true),
        loader_(options) {
    settings_.exposure = view.exposure;
    settings_.hud = view.hud;
    if (!options.aov.empty())
      for (Display d : kDisplays)
        if (options.aov.front() == display_name(d)) settings_.display = d;
    if (!view.script.empty()) script_ = load_script(view.script);
    adopt(std::move(first), true);
  }

  ~Viewer() {
    if (image_texture_) SDL_DestroyTexture(image_texture_);
    if (overlay_texture_) SDL_DestroyTexture(overlay_texture_);
    if (sdl_renderer_) SDL_DestroyRenderer(sdl_renderer_);
    if (window_) SDL_DestroyWindow(window_);
  }

  int run(const std::atomic<bool>* interrupted);

 private:
  struct Settings {
    CameraDescription camera, home;
    int width = 1, height = 1, max_depth = 8;
    SamplingSettings sampling;
    bool unlimited = false;
    AccelKind accel = AccelKind::Bvh;
    Display display = Display::Beauty;
    double exposure = 0;
    bool hud = true, help = false;
  };

  void open_window();
  void adopt(LoadedScene scene, bool first);
  void handle(const SDL_Event& e);
  void key_down(const SDL_Keysym& key, bool repeat);
  void fly(double dt);
  void submit();
  void poll_files();
  bool play_script();
  void refresh_image();
  void draw();
  void save();
  void focus_under_cursor();
  void explain_under_cursor();
  void message(const std::string& text, bool error = false);
  std::vector<std::string> hud_lines(const FrameStatus& s);
  SDL_Rect image_rect() const;
  void push_script_event(const ScriptEvent& e);

  cli::Options options_;
  ViewOptions view_;
  DeviceBackend& backend_;
  ViewRenderer renderer_;
  SceneLoader loader_;
  FileWatch watch_;

  std::shared_ptr<const RenderScene> scene_;
  CameraDescription file_camera_;
  int file_max_depth_ = 0, file_width_ = 0, file_height_ = 0;
  SamplingSettings file_sampling_;
  Settings settings_;
  bool dirty_ = true;  // the camera or a setting changed: a new request is due
  std::uint64_t submitted_ = 0;
  int reloads_ = 0;  // finished reloads (good or bad) since the start
  std::string error_;  // the last reload's error, until a good one
  std::string note_;   // a passing message (saved, printed)
  Clock::time_point note_time_{};

  // Input state (from SDL's events, real or scripted).
  std::set<SDL_Keycode> held_;
  bool shift_ = false;
  int mouse_x_ = 0, mouse_y_ = 0;
  std::uint32_t buttons_ = 0;  // SDL_BUTTON masks

  // Script playback.
  std::vector<ScriptEvent> script_;
  std::size_t script_next_ = 0;
  bool script_waiting_ = false;
  Clock::time_point script_last_{}, wait_start_{};
  int exit_code_ = 0;

  // The window.
  SDL_Window* window_ = nullptr;
  SDL_Renderer* sdl_renderer_ = nullptr;
  SDL_Texture* image_texture_ = nullptr;
  SDL_Texture* overlay_texture_ = nullptr;
  int texture_w_ = 0, texture_h_ = 0, overlay_w_ = 0, overlay_h_ = 0;
  Image frame_;
  FrameStatus frame_status_;
  Rgba8Image rgba_;
  bool redraw_ = true;
  bool renderer_reshow_ = false;  // the same frame again (exposure changed)
  Clock::time_point last_poll_{};
  bool changing_ = false;  // the scene's files changed at the last poll
  std::deque<Clock::time_point> frame_times_;  // images shown in the last second (frames/s)
  Clock::time_point last_hud_{};
  bool quit_ = false;
  // How often the input is looked at: turns of the loop, and the longest time between two.
  std::uint64_t turns_ = 0;
  double longest_gap_ = 0;
  std::deque<Clock::time_point> turn_times_;  // of the last second (the HUD's input rate)
};

void Viewer::adopt(LoadedScene s, bool first) {
  const RenderScene& rs = *s.render;
  // The file's values replace the viewer's where the file changed them; the viewer's own
  // changes (the camera moved, a key pressed) stay where it did not.
  if (first || !same_camera(s.camera, file_camera_)) settings_.camera = settings_.home = s.camera;
  if (first || rs.settings.max_depth != file_max_depth_) settings_.max_depth = rs.settings.max_depth;
  if (first || !same_sampling(rs.sampling, file_sampling_)) settings_.sampling = rs.sampling;
  if (first || rs.camera.nx != file_width_ || rs.camera.ny != file_height_) {
    settings_.width = rs.camera.nx;
    settings_.height = rs.camera.ny;
    if (window_) SDL_SetWindowSize(window_, settings_.width, settings_.height);
  }
  file_camera_ = s.camera;
  file_max_depth_ = rs.settings.max_depth;
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
  r.sampling = settings_.sampling;
  r.unlimited = settings_.unlimited;
  r.time_limit = options_.time_limit;
  r.display = settings_.display;
  r.scale = view_.scale;
  submitted_ = renderer_.submit(std::move(r));
  dirty_ = false;
  redraw_ = true;
}

void Viewer::handle(const SDL_Event& e) {
  switch (e.type) {
    case SDL_QUIT: quit_ = true; break;
    case SDL_WINDOWEVENT: redraw_ = true; break;
    case SDL_KEYDOWN: key_down(e.key.keysym, e.key.repeat != 0); break;
    case SDL_KEYUP:
      held_.erase(e.key.keysym.sym);
      if (e.key.keysym.sym == SDLK_LSHIFT || e.key.keysym.sym == SDLK_RSHIFT) shift_ = false;
      break;
    case SDL_MOUSEBUTTONDOWN:
      buttons_ |= SDL_BUTTON(e.button.button);
      mouse_x_ = e.button.x;
      mouse_y_ = e.button.y;
      break;
    case SDL_MOUSEBUTTONUP:
      buttons_ &= ~SDL_BUTTON(e.button.button);
      mouse_x_ = e.button.x;
      mouse_y_ = e.button.y;
      break;
    case SDL_MOUSEMOTION: {
      const int dx = e.motion.x - mouse_x_, dy = e.motion.y - mouse_y_;
      mouse_x_ = e.motion.x;
      mouse_y_ = e.motion.y;
      if (dx == 0 && dy == 0) break;
      const SDL_Rect rect = image_rect();
      if (buttons_ & SDL_BUTTON_LMASK) {
        // A drag across the whole image turns the view by half a turn, up and down by a quarter.
        orbit(settings_.camera, -kPi * dx / rect.w, kPi / 2 * dy / rect.h);
        dirty_ = true;
      } else if (buttons_ & (SDL_BUTTON_RMASK | SDL_BUTTON_MMASK)) {
        // The point under the cursor at look_at's distance follows the cursor.
        const Real per_pixel = 2 * std::tan(vertical_fov(settings_.camera, settings_.width, settings_.height) / 2) / rect.h;
        pan(settings_.camera, -dx * per_pixel, dy * per_pixel);
        dirty_ = true;
      }
      break;
    }
    case SDL_MOUSEWHEEL:
      if (e.wheel.y != 0) {
        dolly(settings_.camera, std::pow(0.9, double(e.wheel.y)));
        dirty_ = true;
      }
      break;
    default: break;
  }
}

void Viewer::key_down(const SDL_Keysym& key, bool repeat) {
  const bool ctrl = (key.mod & KMOD_CTRL) != 0;
  const SDL_Keycode k = key.sym;
  if (k == SDLK_LSHIFT || k == SDLK_RSHIFT) shift_ = true;
  if (ctrl && k == SDLK_s) {
    if (!repeat) save();
    return;
  }
  switch (k) {
    case SDLK_w: case SDLK_a: case SDLK_s: case SDLK_d: case SDLK_q: case SDLK_e:
      held_.insert(k);
      shift_ = shift_ || (key.mod & KMOD_SHIFT) != 0;
      return;
    default: break;
  }
  bool changed = true;
  switch (k) {
    case SDLK_ESCAPE: quit_ = true; changed = false; break;
    case SDLK_r: settings_.camera = settings_.home; break;
    case SDLK_PLUS: case SDLK_EQUALS: case SDLK_KP_PLUS: zoom(settings_.camera, 1 / 1.1); break;
    case SDLK_MINUS: case SDLK_KP_MINUS: zoom(settings_.camera, 1.1); break;
    case SDLK_f: focus_under_cursor(); break;
    case SDLK_x: explain_under_cursor(); changed = false; break;
    case SDLK_LEFTBRACKET: settings_.max_depth = std::max(1, settings_.max_depth - 1); break;
    case SDLK_RIGHTBRACKET: settings_.max_depth = std::min(64, settings_.max_depth + 1); break;
    case SDLK_m: {
      const auto* it = std::find(std::begin(kSamplers), std::end(kSamplers), settings_.sampling.sampler);
      settings_.sampling.sampler = (it == std::end(kSamplers) || it + 1 == std::end(kSamplers)) ? kSamplers[0] : *(it + 1);
      break;
    }
    case SDLK_COMMA: settings_.sampling.spp = std::max(1, settings_.sampling.spp / 2); break;
    case SDLK_PERIOD: settings_.sampling.spp = std::min(kMaxSpp, std::max(1, settings_.sampling.spp) * 2); break;
    case SDLK_u: settings_.unlimited = !settings_.unlimited; break;
    case SDLK_b: {
      if (repeat) return;
      const std::vector<AccelKind> kinds = accel_kinds();
      auto it = std::find(kinds.begin(), kinds.end(), settings_.accel);
      const AccelKind next = (it == kinds.end() || it + 1 == kinds.end()) ? kinds.front() : *(it + 1);
      loader_.request(next);
      message(fmt::format("building the {} accelerator ...", accel_name(next)));
      changed = false;
      break;
    }
    case SDLK_v: {
      const auto* it = std::find(std::begin(kDisplays), std::end(kDisplays), settings_.display);
      settings_.display = (it + 1 == std::end(kDisplays)) ? kDisplays[0] : *(it + 1);
      break;
    }
    case SDLK_9: case SDLK_KP_9: settings_.exposure -= 0.5; renderer_reshow_ = true; changed = false; break;
    case SDLK_0: case SDLK_KP_0: settings_.exposure += 0.5; renderer_reshow_ = true; changed = false; break;
    case SDLK_p:
      console::out("{}", camera_yaml(settings_.camera));
      note_ = "camera printed on stdout";
      note_time_ = Clock::now();
      changed = false;
      break;
    case SDLK_l: if (!repeat) loader_.request(settings_.accel); changed = false; break;
    case SDLK_TAB: settings_.hud = !settings_.hud; redraw_ = true; changed = false; break;
    case SDLK_h: case SDLK_F1: settings_.help = !settings_.help; redraw_ = true; changed = false; break;
    default: changed = false; break;
  }
  if (changed) dirty_ = true;
}

void Viewer::fly(double dt) {
  if (held_.empty()) return;
  const Real step = Real(kFlySpeed * dt * (shift_ ? 5 : 1)) * distance_to_look_at(settings_.camera);
  const Real right = step * ((held_.count(SDLK_d) ? 1 : 0) - (held_.count(SDLK_a) ? 1 : 0));
  const Real up = step * ((held_.count(SDLK_e) ? 1 : 0) - (held_.count(SDLK_q) ? 1 : 0));
  const Real forward = step * ((held_.count(SDLK_w) ? 1 : 0) - (held_.count(SDLK_s) ? 1 : 0));
  if (right == 0 && up == 0 && forward == 0) return;
  view::fly(settings_.camera, right, up, forward);
  dirty_ = true;
}

void Viewer::focus_under_cursor() {
  const SDL_Rect rect = image_rect();
  const double fx = (mouse_x_ - rect.x + 0.5) / rect.w, fy = (mouse_y_ - rect.y + 0.5) / rect.h;
  if (fx < 0 || fx >= 1 || fy < 0 || fy >= 1) return;
  SceneView view = scene_->view();
  try {
    view.camera = build_camera(settings_.camera, settings_.width, settings_.height);
  } catch (const Error&) {
    return;
  }
  const Ray ray = view.camera.generate_ray(Real(fx * settings_.width), Real((1 - fy) * settings_.height));
  const Hit hit = closest_hit(view, ray, 0, kInfinity);
  if (!hit.found()) {
    message("F: nothing under the cursor");
    return;
  }
  focus_on(settings_.camera, ray.at(hit.t));
}

// X: the ray tree of sample 0 of the full-resolution pixel under the cursor, with the window's
// camera, max depth and sampler (render/explain.h; what `strahl --explain` prints for them).
void Viewer::explain_under_cursor() {
  const SDL_Rect rect = image_rect();
  const double fx = (mouse_x_ - rect.x + 0.5) / rect.w, fy = (mouse_y_ - rect.y + 0.5) / rect.h;
  if (!scene_ || fx < 0 || fx >= 1 || fy < 0 || fy >= 1) return;
  SceneView view = scene_->view();
  view.settings.max_depth = settings_.max_depth;
  try {
    view.camera = build_camera(settings_.camera, settings_.width, settings_.height);
  } catch (const Error&) {
    return;
  }
  const int x = std::min(settings_.width - 1, int(fx * settings_.width));
  const int row = std::min(settings_.height - 1, int(fy * settings_.height));
  console::out("{}", explain_pixel(*scene_, view, settings_.sampling, x, row).text);
  note_ = fmt::format("pixel ({}, {}) explained on stdout", x, row);
  note_time_ = Clock::now();
  redraw_ = true;
}

void Viewer::save() {
  Image image;
  FrameStatus s;
  if (!renderer_.take_image(image, s, true) || image.width() == 0) {
    message("nothing to save yet");
    return;
  }
  namespace fs = std::filesystem;
  fs::path base = cli::output_path(options_);
  WriteOptions w;
  w.linear = options_.linear;
  if (settings_.display != Display::Beauty) {
    // AOVs are values, not colours: EXR, as strahl --aov writes them.
    base = base.parent_path() / (base.stem().string() + "." + display_name(settings_.display) + ".exr");
  }
  try {
    const fs::path saved = save_numbered(image, base, w);
    message(fmt::format("saved {} ({}x{}, {:g} spp{})", saved.string(), image.width(), image.height(), s.spp,
                        s.finished ? "" : ", still rendering"));
  } catch (const std::exception& e) {
    message(e.what(), true);
  }
}

void Viewer::poll_files() {
  const Clock::time_point now = Clock::now();
  if (seconds_between(last_poll_, now) >= view_.reload_poll) {
    last_poll_ = now;
    // Reload once the files have stopped changing for a whole poll interval: an editor or a
    // program still writing them would otherwise be caught half way.
    if (watch_.changed()) changing_ = true;
    else if (changing_) {
      changing_ = false;
      loader_.request(settings_.accel);
    }
  }
  if (const std::string failure = backend_.take_failure(); !failure.empty()) {
    message(failure, true);
    dirty_ = true;  // the stopped frame again, on the CPU
  }
  if (std::optional<SceneLoader::Result> r = loader_.take()) {
    ++reloads_;
    if (r->scene) {
      const double seconds = r->scene->seconds;
      adopt(std::move(*r->scene), false);
      message(fmt::format("reloaded ({:.2f} s), accel {}", seconds, accel_name(settings_.accel)));
    } else {
      message(r->error + "\n(showing the last good scene)", true);
    }
  }
}

void Viewer::push_script_event(const ScriptEvent& e) {
  SDL_Event ev{};
  const Uint32 id = SDL_GetWindowID(window_);
  using K = ScriptEvent::Kind;
  auto key_event = [&](Uint32 type, const std::string& name, bool ctrl, bool shift) {
    SDL_Event k{};
    k.type = type;
    k.key.windowID = id;
    k.key.state = type == SDL_KEYDOWN ? SDL_PRESSED : SDL_RELEASED;
    k.key.keysym.sym = SDL_GetKeyFromName(name.c_str());
    if (k.key.keysym.sym == SDLK_UNKNOWN) {
      console::err("strahl-view: error: {}:{}: unknown key '{}'\n", view_.script, e.line, name);
      exit_code_ = 2;
      quit_ = true;
      return;
    }
    k.key.keysym.scancode = SDL_GetScancodeFromKey(k.key.keysym.sym);
    k.key.keysym.mod = Uint16((ctrl ? KMOD_LCTRL : 0) | (shift ? KMOD_LSHIFT : 0));
    SDL_PushEvent(&k);
  };
  switch (e.kind) {
    case K::MouseDown: case K::MouseUp:
      ev.type = e.kind == K::MouseDown ? SDL_MOUSEBUTTONDOWN : SDL_MOUSEBUTTONUP;
      ev.button.windowID = id;
      ev.button.button = Uint8(e.button);
      ev.button.state = e.kind == K::MouseDown ? SDL_PRESSED : SDL_RELEASED;
      ev.button.clicks = 1;
      ev.button.x = e.x;
      ev.button.y = e.y;
      SDL_PushEvent(&ev);
      break;
    case K::MouseMove:
      ev.type = SDL_MOUSEMOTION;
      ev.motion.windowID = id;
      ev.motion.state = buttons_;
      ev.motion.x = e.x;
      ev.motion.y = e.y;
      ev.motion.xrel = e.x - mouse_x_;
      ev.motion.yrel = e.y - mouse_y_;
      SDL_PushEvent(&ev);
      break;
    case K::Wheel:
      ev.type = SDL_MOUSEWHEEL;
      ev.wheel.windowID = id;
      ev.wheel.y = e.amount;
      ev.wheel.direction = SDL_MOUSEWHEEL_NORMAL;
      SDL_PushEvent(&ev);
      break;
    case K::Key:
      key_event(SDL_KEYDOWN, e.key, e.ctrl, e.shift);
      key_event(SDL_KEYUP, e.key, e.ctrl, e.shift);
      break;
    case K::KeyDown: key_event(SDL_KEYDOWN, e.key, e.ctrl, e.shift); break;
    case K::KeyUp: key_event(SDL_KEYUP, e.key, e.ctrl, e.shift); break;
    case K::Quit:
      ev.type = SDL_QUIT;
      SDL_PushEvent(&ev);
      break;
    default: break;
  }
}

// One script step per turn of the loop, so that the events pushed are handled (and the request
// they make submitted) before the next step looks at the frame.
bool Viewer::play_script() {
  if (script_next_ >= script_.size()) return true;
  const ScriptEvent& e = script_[script_next_];
  const Clock::time_point now = Clock::now();
  using K = ScriptEvent::Kind;
  if (script_waiting_) {
    const FrameStatus s = renderer_.status();
    const bool current = !dirty_ && s.request == submitted_ && !s.interactive && !loader_.busy();
    bool done = false;
    switch (e.kind) {
      case K::WaitSpp: done = current && (s.spp >= e.amount || s.finished); break;
      case K::WaitStill: done = current && s.finished; break;
      case K::WaitReload: done = reloads_ >= e.amount; break;
      default: done = true; break;
    }
    if (!done) {
      if (seconds_between(wait_start_, now) > kScriptWaitLimit) {
        console::err("strahl-view: error: {}:{}: the wait took longer than {} s\n", view_.script, e.line, kScriptWaitLimit);
        exit_code_ = 2;
        quit_ = true;
      }
      return false;
    }
    script_waiting_ = false;
    script_last_ = now;
    ++script_next_;
    return false;
  }
  if (seconds_between(script_last_, now) < e.delay) return false;
  if (e.kind == K::WaitSpp || e.kind == K::WaitStill || e.kind == K::WaitReload) {
    script_waiting_ = true;
    wait_start_ = now;
    return false;
  }
  push_script_event(e);
  script_last_ = now;
  ++script_next_;
  return false;
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
  l.push_back(fmt::format("depth {}  sampler {}  spp {}  accel {}", settings_.max_depth,
                          sampler_name(settings_.sampling.sampler), settings_.sampling.spp, accel_name(settings_.accel)));
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

}  // namespace

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
