#pragma once
// The viewer's side of the render job (render/render_job.h): one thread that renders whatever
// the window asks for last, through a TileBackend (the CPU's now, the GPU's later), while the
// window thread reads the accumulated frame at any time. No render logic of its own: every
// sample comes from a RenderJob, so the still image is the one `strahl` writes.
//
// Two kinds of frame:
//   interactive  one sample per pixel at 1/scale of the resolution (the camera is moving); the
//                scale adapts so that a frame takes about kFrameBudget; a new request never
//                cancels one (it is taken next), so moving keeps a steady frame rate
//   still        full resolution, passes of one sample per pixel accumulated up to the target
//                (or without end); cancelled at once by a new request
// After an interactive frame with nothing new asked for, the still frame of the same request
// follows by itself.

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "strahl/image/image.h"
#include "strahl/render/render_job.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/scene.h"

namespace strahl::view {

// What the window shows: the image, or one of the AOVs of render/aov.h.
enum class Display { Beauty, Depth, Normal, Albedo, Id };
const char* display_name(Display d);

inline constexpr double kFrameBudget = 1.0 / 30;  // seconds an interactive frame may take

struct FrameRequest {
  std::shared_ptr<const RenderScene> scene;
  CameraDescription camera;
  int width = 1, height = 1;  // the full resolution
  int max_depth = 8;
  IntegratorKind integrator = IntegratorKind::Whitted;
  SamplingSettings sampling;  // of the still frames; interactive frames take 1 sample per pixel
  bool unlimited = false;     // still frames go on past sampling.spp (up to kMaxSpp)
  double time_limit = 0;      // still frames stop after this many seconds (0: none)
  Display display = Display::Beauty;
  bool interactive = true;    // start with an interactive frame (false: straight to the still one)
  int scale = 0;              // interactive frames at 1/scale resolution; 0: adapt
};

// A look at the frame being rendered.
struct FrameStatus {
  std::uint64_t request = 0;   // which request it belongs to (submit()'s number)
  bool interactive = false;
  Display display = Display::Beauty;
  bool finished = false;       // every sample asked for is taken (or the time limit reached)
  int width = 0, height = 0;   // of this frame
  int scale = 1;
  double spp = 0;              // samples per pixel taken so far (mean)
  std::uint32_t target_spp = 0;
  RayCounters rays;            // of this frame so far (complete after each pass)
  double seconds = 0;          // rendering time of this frame so far
  std::string error;           // the camera could not be built (the frame is empty)
};

class ViewRenderer {
 public:
  // `backend` renders the tiles (must outlive this); `threads` also runs the AOV frames. With
  // `yield_to_window`, the render thread and oneTBB's workers run at a lower priority (nice +5)
  // than the rest of the process, so that the window's thread gets a core when it wakes.
  ViewRenderer(TileBackend& backend, int threads, int tile_size, bool yield_to_window = false);
  ~ViewRenderer();  // cancels and joins
  ViewRenderer(const ViewRenderer&) = delete;
  ViewRenderer& operator=(const ViewRenderer&) = delete;

  // Renders this from now on (see above); returns its number.
  std::uint64_t submit(FrameRequest request);

  // The status of the newest frame with something to show; the image too when `image` is given
  // and it changed since the last call that took one (returns whether it did).
  FrameStatus status() const;
  // `always`: also when nothing changed (saving).
  bool take_image(Image& image, FrameStatus& status, bool always = false);

  // Renders one interactive frame at `scale` on the calling thread and returns it (the
  // benchmark; the render thread must be idle).
  FrameStatus render_interactive(const FrameRequest& request, int scale, Image* image = nullptr);

  // Interactive frames' resolution divisor now (adapted to the frame budget).
  int scale() const;

 private:
  struct Active;  // the frame being rendered
  void loop();
  void render(const FrameRequest& request, bool interactive, std::uint64_t number);
  int choose_scale(const FrameRequest& request) const;

  struct Yield;  // the oneTBB observer that lowers the workers' priority
  TileBackend& backend_;
  int threads_, tile_size_;
  bool yield_;
  std::unique_ptr<Yield> yield_observer_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<FrameRequest> pending_;
  std::uint64_t submitted_ = 0, pending_number_ = 0;
  mutable std::shared_ptr<Active> shown_;  // the newest frame with something to show
  std::shared_ptr<Active> running_;        // the frame being rendered
  std::uint64_t frames_ = 0;               // Active::serial of the last frame started
  std::uint64_t taken_serial_ = 0, taken_samples_ = 0;  // what take_image() last returned
  double pixels_per_second_ = 0;     // of interactive frames, measured
  bool quit_ = false;
  std::thread thread_;  // last: starts once the members above exist
};

}  // namespace strahl::view
