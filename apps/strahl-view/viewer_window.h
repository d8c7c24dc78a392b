#pragma once
// The viewer's window and its state (viewer.h is the interface): shared by viewer.cpp (the window,
// the loop, the picture) and viewer_input.cpp (keys, mouse, scripts, saving, reloads).

#include <SDL.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "camera_control.h"
#include "display.h"
#include "script.h"
#include "setup.h"
#include "text.h"
#include "view_renderer.h"
#include "viewer.h"

namespace strahl::view {

using Clock = std::chrono::steady_clock;

inline double seconds_between(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

inline constexpr SamplerKind kSamplers[] = {SamplerKind::Grid, SamplerKind::Stratified, SamplerKind::Random,
                                            SamplerKind::Sobol, SamplerKind::Adaptive};
inline constexpr Display kDisplays[] = {Display::Beauty, Display::Depth, Display::Normal, Display::Albedo, Display::Id};
inline constexpr double kScriptWaitLimit = 300;  // seconds a script's `wait` may take
inline constexpr double kFlySpeed = 0.6;         // distances to look_at per second
inline constexpr Rgba kWhite{235, 235, 235, 255}, kRed{255, 110, 100, 255}, kYellow{255, 220, 120, 255};

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
    IntegratorKind integrator = IntegratorKind::Whitted;
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
  IntegratorKind file_integrator_ = IntegratorKind::Whitted;
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

}  // namespace strahl::view
