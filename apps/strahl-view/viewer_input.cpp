// The viewer's input (viewer_window.h): keys and the mouse (fly, orbit, focus, explain), script
// playback with its waits, saving the picture, and the scene's files watched and reloaded.

#include <SDL.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "camera_yaml.h"
#include "console.h"
#include "keys.h"
#include "save.h"
#include "strahl/render/explain.h"
#include "strahl/render/intersect_scene.h"
#include "strahl/scene/camera_build.h"
#include "viewer_window.h"

namespace strahl::view {

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
    case SDLK_g:
      settings_.integrator =
          settings_.integrator == IntegratorKind::Whitted ? IntegratorKind::Path : IntegratorKind::Whitted;
      break;
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
  view.settings.integrator = settings_.integrator;
  if (const std::string why = explain_refusal(view); !why.empty()) {
    note_ = why;
    note_time_ = Clock::now();
    redraw_ = true;
    return;
  }
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

}  // namespace strahl::view
