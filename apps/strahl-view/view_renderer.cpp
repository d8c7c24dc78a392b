#include "view_renderer.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_scheduler_observer.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include "strahl/render/aov.h"
#include "strahl/scene/camera_build.h"
#include "strahl/util/error.h"

namespace strahl::view {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

const char* display_name(Display d) {
  switch (d) {
    case Display::Beauty: return "image";
    case Display::Depth: return "depth";
    case Display::Normal: return "normal";
    case Display::Albedo: return "albedo";
    case Display::Id: return "id";
  }
  return "image";
}

struct ViewRenderer::Active {
  std::uint64_t serial = 0;  // unique per frame
  std::uint64_t number = 0;
  bool interactive = false;
  int width = 0, height = 0, scale = 1;
  std::uint32_t target = 0;
  std::shared_ptr<const RenderScene> scene;  // the job's view points into it
  std::unique_ptr<RenderJob> job;            // beauty frames
  Display display = Display::Beauty;
  Image aov;                                 // AOV frames, complete once `finished`
  std::atomic<bool> cancel{false}, finished{false};
  std::atomic<std::uint64_t> camera_rays{0}, shadow_rays{0}, reflection_rays{0}, refraction_rays{0};
  std::atomic<double> seconds{0};
  Clock::time_point start{};
  std::string error;

  void add(const RayCounters& r) {
    camera_rays.fetch_add(r.camera, std::memory_order_relaxed);
    shadow_rays.fetch_add(r.shadow, std::memory_order_relaxed);
    reflection_rays.fetch_add(r.reflection, std::memory_order_relaxed);
    refraction_rays.fetch_add(r.refraction, std::memory_order_relaxed);
  }
  // Something to show: an interactive frame once complete, a still one after its first pass.
  bool presentable() const {
    if (finished.load()) return true;
    return !interactive && job && job->passes_done() >= 1;
  }
  std::uint64_t samples() const {
    if (job) return job->samples_done();
    return finished.load() ? std::uint64_t(width) * std::uint64_t(height) : 0;
  }
  FrameStatus status() const {
    FrameStatus s;
    s.request = number;
    s.interactive = interactive;
    s.display = display;
    s.finished = finished.load();
    s.width = width;
    s.height = height;
    s.scale = scale;
    const double pixels = std::max(1.0, double(width) * double(height));
    s.spp = double(samples()) / pixels;
    s.target_spp = target;
    s.rays.camera = camera_rays.load();
    s.rays.shadow = shadow_rays.load();
    s.rays.reflection = reflection_rays.load();
    s.rays.refraction = refraction_rays.load();
    s.seconds = s.finished ? seconds.load() : seconds_since(start);
    s.error = error;
    return s;
  }
};

namespace {
// Linux gives every thread its own nice value; lowering it needs no privilege (failure is harmless).
void lower_this_threads_priority() { setpriority(PRIO_PROCESS, id_t(::syscall(SYS_gettid)), 5); }
}  // namespace

struct ViewRenderer::Yield : tbb::task_scheduler_observer {
  Yield() { observe(true); }  // every arena of the process: only rendering uses oneTBB here
  ~Yield() override { observe(false); }
  void on_scheduler_entry(bool worker) override {
    if (worker) lower_this_threads_priority();
  }
};

ViewRenderer::ViewRenderer(TileBackend& backend, int threads, int tile_size, bool yield_to_window)
    : backend_(backend),
      threads_(threads),
      tile_size_(tile_size),
      yield_(yield_to_window),
      yield_observer_(yield_to_window ? std::make_unique<Yield>() : nullptr),
      thread_([this] { loop(); }) {}

ViewRenderer::~ViewRenderer() {
  {
    std::lock_guard lock(mutex_);
    quit_ = true;
    if (running_) running_->cancel.store(true);
  }
  wake_.notify_all();
  thread_.join();
}

std::uint64_t ViewRenderer::submit(FrameRequest request) {
  std::uint64_t number;
  {
    std::lock_guard lock(mutex_);
    number = ++submitted_;
    pending_ = std::move(request);
    pending_number_ = number;
    // A still frame gives way at once; an interactive one is finished first (steady frame rate).
    if (running_ && !running_->interactive && !running_->finished.load()) running_->cancel.store(true);
  }
  wake_.notify_all();
  return number;
}

void ViewRenderer::loop() {
  if (yield_) lower_this_threads_priority();
  for (;;) {
    FrameRequest request;
    std::uint64_t number;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return quit_ || pending_.has_value(); });
      if (quit_) return;
      request = std::move(*pending_);
      pending_.reset();
      number = pending_number_;
    }
    if (request.interactive) {
      render(request, true, number);
      std::lock_guard lock(mutex_);
      if (quit_) return;
      if (pending_) continue;  // moving on: the next interactive frame
    }
    render(request, false, number);
  }
}

int ViewRenderer::choose_scale(const FrameRequest& request) const {
  const double pixels = double(request.width) * double(request.height);
  // Before any measurement: about 640×360 pixels.
  const double affordable = pixels_per_second_ > 0 ? pixels_per_second_ * kFrameBudget : 640.0 * 360.0;
  const int s = int(std::ceil(std::sqrt(pixels / std::max(affordable, 1.0)) - 1e-9));
  return std::clamp(s, 1, 16);
}

int ViewRenderer::scale() const {
  std::lock_guard lock(mutex_);
  return shown_ ? shown_->scale : 1;
}

void ViewRenderer::render(const FrameRequest& request, bool interactive, std::uint64_t number) {
  auto a = std::make_shared<Active>();
  a->number = number;
  a->interactive = interactive;
  a->scale = interactive ? (request.scale > 0 ? request.scale : choose_scale(request)) : 1;
  a->width = std::max(1, request.width / a->scale);
  a->height = std::max(1, request.height / a->scale);
  a->scene = request.scene;
  a->display = request.display;
  a->start = Clock::now();

  SceneView view = request.scene->view();
  view.settings.max_depth = request.max_depth;
  view.settings.integrator = request.integrator;
  try {
    view.camera = build_camera(request.camera, a->width, a->height);
  } catch (const Error& e) {
    a->error = e.what();
    a->finished.store(true);
    std::lock_guard lock(mutex_);
    a->serial = ++frames_;
    running_ = shown_ = a;
    return;
  }

  if (request.display == Display::Beauty) {
    SamplingSettings s = request.sampling;
    if (interactive) s.spp = 1;
    else if (request.unlimited) s.spp = kMaxSpp;
    JobOptions o;
    o.tile_size = tile_size_;
    o.cancel = &a->cancel;
    o.progressive = !interactive;
    o.max_pass_samples = interactive ? 0 : 1;
    o.time_limit = interactive ? 0 : request.time_limit;
    Active* raw = a.get();
    o.on_tile = [raw](const TileWork& t) { raw->add(t.counters); };
    a->target = std::uint32_t(effective_spp(s.sampler, s.spp));
    a->job = std::make_unique<RenderJob>(view, s, std::move(o));
  } else {
    a->target = 1;
  }
  {
    std::lock_guard lock(mutex_);
    a->serial = ++frames_;
    running_ = a;
    if (quit_ || (pending_ && !interactive)) return;  // already superseded
  }

  if (a->job) {
    a->job->run(backend_);
    a->finished.store(!a->job->stats().cancelled);
  } else {
    // The AOV's first-hit quantities of every pixel, on `threads_` threads.
    Image img(a->width, a->height);
    tbb::task_arena arena(threads_ > 0 ? threads_ : tbb::task_arena::automatic);
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, a->height), [&](const tbb::blocked_range<int>& rows) {
        for (int row = rows.begin(); row != rows.end(); ++row) {
          if (a->cancel.load(std::memory_order_relaxed)) return;
          for (int x = 0; x < a->width; ++x) {
            const AovSample s = aov_sample(view, x, row);
            Rgb& p = img.at(x, row);
            switch (request.display) {
              case Display::Depth: p = {float(s.depth), float(s.depth), float(s.depth)}; break;
              case Display::Normal: p = {float(s.normal.x), float(s.normal.y), float(s.normal.z)}; break;
              case Display::Albedo: p = {float(s.albedo.x), float(s.albedo.y), float(s.albedo.z)}; break;
              default: p = {float(s.id), float(s.id), float(s.id)}; break;
            }
          }
        }
      });
    });
    a->camera_rays.store(std::uint64_t(a->width) * std::uint64_t(a->height));
    if (!a->cancel.load()) {
      a->aov = std::move(img);
      a->finished.store(true);
    }
  }
  a->seconds.store(seconds_since(a->start));
  if (interactive && a->finished.load() && a->job) {
    const double rate = double(a->width) * double(a->height) / std::max(a->seconds.load(), 1e-6);
    std::lock_guard lock(mutex_);
    pixels_per_second_ = pixels_per_second_ > 0 ? 0.5 * pixels_per_second_ + 0.5 * rate : rate;
  }
}

FrameStatus ViewRenderer::status() const {
  std::lock_guard lock(mutex_);
  if (running_ && running_->presentable()) shown_ = running_;
  return shown_ ? shown_->status() : FrameStatus{};
}

bool ViewRenderer::take_image(Image& image, FrameStatus& status, bool always) {
  std::shared_ptr<Active> a;
  {
    std::lock_guard lock(mutex_);
    if (running_ && running_->presentable()) shown_ = running_;
    a = shown_;
  }
  if (!a) return false;
  status = a->status();
  const std::uint64_t samples = a->samples();
  if (!always && a->serial == taken_serial_ && samples == taken_samples_) return false;
  if (a->job) image = a->job->image();
  else if (a->finished.load()) image = a->aov;
  else return false;
  taken_serial_ = a->serial;
  taken_samples_ = samples;
  status = a->status();
  return true;
}

FrameStatus ViewRenderer::render_interactive(const FrameRequest& request, int scale, Image* image) {
  FrameRequest r = request;
  r.scale = scale;
  std::uint64_t number;
  {
    std::lock_guard lock(mutex_);
    number = ++submitted_;
  }
  render(r, true, number);
  std::shared_ptr<Active> a;
  {
    std::lock_guard lock(mutex_);
    a = running_;
  }
  if (image && a->job) *image = a->job->image();
  return a->status();
}

}  // namespace strahl::view
