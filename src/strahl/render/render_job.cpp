#include "strahl/render/render_job.h"

#include <algorithm>
#include <condition_variable>
#include <thread>

#include "strahl/render/adaptive.h"

namespace strahl {

namespace {

template <class Clock>
typename Clock::duration seconds(double s) {
  return std::chrono::duration_cast<typename Clock::duration>(std::chrono::duration<double>(s));
}

// Sets the job's stop at the time limit, from a thread of its own, so that the per-sample check
// stays two atomic loads instead of a clock read.
class Watchdog {
 public:
  template <class TimePoint, class OnTimeout>
  Watchdog(TimePoint deadline, OnTimeout on_timeout)
      : thread_([this, deadline, on_timeout] {
          std::unique_lock lock(mutex_);
          if (!wake_.wait_until(lock, deadline, [this] { return finished_; })) on_timeout();
        }) {}
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;
  ~Watchdog() {
    {
      std::lock_guard lock(mutex_);
      finished_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  bool finished_ = false;
  std::thread thread_;  // last: starts once the members above exist
};

}  // namespace

FilmLayout film_layout_for(const SceneView& view, const SamplingSettings& sampling) {
  return FilmLayout(view.camera.nx, view.camera.ny, sampling.filter, sampling.sampler == SamplerKind::Adaptive);
}

RenderJob::RenderJob(const SceneView& view, const SamplingSettings& sampling, JobOptions options)
    : view_(view),
      sampling_(sampling),
      sampler_(make_pixel_sampler(sampling)),
      options_(std::move(options)),
      film_(film_layout_for(view, sampling)),
      stop_(options_.cancel) {
  width_ = view.camera.nx;
  height_ = view.camera.ny;
  tile_ = std::max(1, options_.tile_size);
  tiles_x_ = (width_ + tile_ - 1) / tile_;
  tiles_y_ = (height_ + tile_ - 1) / tile_;
  max_spp_ = std::uint32_t(effective_spp(sampling.sampler, sampling.spp));
  adaptive_ = sampling.sampler == SamplerKind::Adaptive;
  if (adaptive_) planner_ = std::make_unique<AdaptivePlanner>();
  progressive_ = adaptive_ || options_.time_limit > 0 || options_.checkpoint_interval > 0 || options_.progressive;
  const std::size_t pixels = std::size_t(width_) * std::size_t(height_);
  counts_ = ZeroedArray<std::uint32_t>(pixels);  // fresh pages, first touched by the threads that deliver tiles
  // First pass: all samples, or 1 (progressive), or the adaptive minimum.
  dense_pending_ =
      adaptive_ ? std::min(max_spp_, std::uint32_t(std::max(1, sampling.adaptive_min))) : progressive_ ? 1 : max_spp_;
  take_pass();
  planned_.store(std::uint64_t(max_spp_) * pixels);
}

RenderJob::~RenderJob() = default;

void RenderJob::cancel() {
  cancelled_.store(true, std::memory_order_relaxed);
  stop_.request();
}

void RenderJob::run(TileBackend& backend) {
  start_ = Clock::now();
  next_checkpoint_ = start_ + seconds<Clock>(std::max(0.0, options_.checkpoint_interval));
  const bool timed = options_.time_limit > 0;
  const auto deadline = start_ + seconds<Clock>(timed ? options_.time_limit : 0.0);
  const auto time_out = [this] {
    out_of_time_.store(true, std::memory_order_relaxed);
    stop_.request();
  };
  std::optional<Watchdog> watchdog;
  if (timed) watchdog.emplace(deadline, time_out);

  bool more = !counts_.empty() && dense_add_ > 0;  // (the first pass is dense)
  while (more) {
    next_.store(0);
    backend.render_pass(*this);
    passes_.fetch_add(1, std::memory_order_relaxed);
    if (timed && Clock::now() >= deadline) time_out();
    if (stop_.requested()) {
      if (!out_of_time_.load()) cancelled_.store(true, std::memory_order_relaxed);
      break;
    }
    more = plan_next_pass();
  }
  watchdog.reset();
  seconds_ = std::chrono::duration<double>(Clock::now() - start_).count();
}

bool RenderJob::take_pass() {
  std::uint64_t n = 0;
  const std::uint32_t cap = options_.max_pass_samples;
  if (!sparse_) {
    dense_taken_ += dense_add_;  // the pass before this one is complete
    dense_add_ = cap > 0 ? std::min(dense_pending_, cap) : dense_pending_;
    dense_pending_ -= dense_add_;
    return dense_add_ > 0 && !counts_.empty();
  }
  for (const std::uint32_t p : pass_pixels_) add_[p] = 0;
  pass_pixels_.clear();
  std::fill(busy_.begin(), busy_.end(), std::uint8_t(0));
  std::size_t keep = 0;
  for (const std::uint32_t p : pending_pixels_) {
    const std::uint32_t a = cap > 0 ? std::min(pending_[p], cap) : pending_[p];
    if (a == 0) continue;
    add_[p] = a;
    pending_[p] -= a;
    n += a;
    pass_pixels_.push_back(p);
    const int x = int(p % std::uint32_t(width_)), row = int(p / std::uint32_t(width_));
    busy_[std::size_t(row / tile_) * std::size_t(tiles_x_) + std::size_t(x / tile_)] = 1;
    if (pending_[p] > 0) pending_pixels_[keep++] = p;
  }
  pending_pixels_.resize(keep);
  return n > 0;
}

bool RenderJob::plan_next_pass() {
  ++pass_;
  if (take_pass()) return true;  // the rest of a pass split by max_pass_samples
  if (adaptive_) {
    if (!sparse_) {  // from now on the passes are sparse (the dense pass left nothing pending)
      busy_.assign(std::size_t(tile_count()), 0);
      add_ = ZeroedArray<std::uint32_t>(counts_.size());
      sparse_ = true;
    }
    // Samples the render may still take in all: an upper bound that shrinks pass by pass (the
    // planner sums max_spp − count over the pixels it plans more for).
    std::uint64_t headroom = 0;
    planner_->plan(film_, counts_, max_spp_, sampling_.adaptive_threshold, pending_, false, &headroom);
    pending_pixels_ = planner_->planned();
    planned_.store(done_.load() + headroom);
  } else {
    // Double every pixel's count (all pixels have the same).
    dense_pending_ = std::min(dense_taken_, max_spp_ - dense_taken_);
  }
  return take_pass();
}

TileWork RenderJob::tile(int index) const {
  TileWork w;
  tile(index, w);
  return w;
}

void RenderJob::tile(int index, TileWork& w) const {
  w.pass = pass_;
  w.index = index;
  w.rect.x0 = (index % tiles_x_) * tile_;
  w.rect.row0 = (index / tiles_x_) * tile_;
  w.rect.x1 = std::min(width_, w.rect.x0 + tile_);
  w.rect.row1 = std::min(height_, w.rect.row0 + tile_);
  const std::size_t n = w.rect.pixels(), tw = std::size_t(w.rect.width());
  w.first.resize(n);
  w.count.resize(n);
  for (int row = w.rect.row0; row < w.rect.row1; ++row) {
    const std::size_t p = std::size_t(row) * std::size_t(width_) + std::size_t(w.rect.x0);
    const std::size_t i = std::size_t(row - w.rect.row0) * tw;
    if (sparse_) {
      std::copy_n(&counts_[p], tw, &w.first[i]);
      std::copy_n(&add_[p], tw, &w.count[i]);
    } else {  // (counts_ not read: its pages are first touched by deliver's writes)
      std::fill_n(&w.first[i], tw, dense_taken_);
      std::fill_n(&w.count[i], tw, dense_add_);
    }
  }
  film_.begin_tile(w);
}

// A replayed tile fits the current pass: the same rectangle, every sample it should have, and
// buffers of the film's layout (a journal is checked against the scene and settings as a whole;
// this guards the indexing).
bool RenderJob::replayable(const TileWork& done, int index) const {
  const TileWork want = tile(index);
  const std::size_t n = want.rect.pixels();
  if (done.pass != pass_ || done.rect.x0 != want.rect.x0 || done.rect.row0 != want.rect.row0 ||
      done.rect.x1 != want.rect.x1 || done.rect.row1 != want.rect.row1 || done.taken != want.count)
    return false;
  if (film_.pixel_local() ? done.local.size() != n * 4 : done.fixed.size() != want.fixed.size()) return false;
  if (!film_.pixel_local() && (done.bx0 != want.bx0 || done.brow0 != want.brow0 || done.bw != want.bw || done.bh != want.bh))
    return false;
  return film_.layout().keeps_stats() ? done.stats.size() == n : done.stats.empty();
}

std::optional<TileWork> RenderJob::next_tile() {
  TileWork w;
  if (!next_tile(w)) return std::nullopt;
  return w;
}

bool RenderJob::next_tile(TileWork& work) {
  while (!stop_.requested()) {
    const int i = next_.fetch_add(1, std::memory_order_relaxed);
    if (i >= tile_count()) break;
    // Tiles with nothing to do in this pass (adaptive sampling) are not handed out; dense passes
    // give every pixel samples.
    if (sparse_ && busy_[std::size_t(i)] == 0) continue;
    if (options_.replay) {
      std::optional<TileWork> done = options_.replay(pass_, i);
      if (done && replayable(*done, i)) {
        replayed_.fetch_add(1, std::memory_order_relaxed);
        deliver(*done);
        continue;
      }
    }
    tile(i, work);
    return true;
  }
  return false;
}

void RenderJob::deliver(const TileWork& work) {
  film_.merge(work);
  const TileRect& r = work.rect;
  const std::size_t tw = std::size_t(r.width());
  for (int row = r.row0; row < r.row1; ++row) {
    std::uint32_t* count = &counts_[std::size_t(row) * std::size_t(width_) + std::size_t(r.x0)];
    const std::uint32_t* taken = &work.taken[std::size_t(row - r.row0) * tw];
    // A dense pass's counts are written, not read: the first touch of counts_'s fresh pages is a
    // write (reading one first maps the shared zero page, and the write after it then costs a
    // copy-on-write fault and a TLB flush on every core).
    if (sparse_)
      for (std::size_t k = 0; k < tw; ++k) count[k] += taken[k];
    else
      for (std::size_t k = 0; k < tw; ++k) count[k] = dense_taken_ + taken[k];
  }
  const std::uint64_t n = work.samples_taken();
  {
    std::lock_guard lock(deliver_mutex_);
    counters_ += work.counters;
  }
  if (options_.on_tile) {
    std::lock_guard lock(on_tile_mutex_);
    options_.on_tile(work);
  }
  report(done_.fetch_add(n) + n);
  if (options_.checkpoint && options_.checkpoint_interval > 0) {
    std::unique_lock lock(checkpoint_mutex_, std::try_to_lock);
    if (lock.owns_lock() && Clock::now() >= next_checkpoint_) {
      options_.checkpoint(film_.resolve());
      next_checkpoint_ = Clock::now() + seconds<Clock>(options_.checkpoint_interval);
    }
  }
}

void RenderJob::report(std::uint64_t now_done) {
  if (!options_.progress) return;
  const std::uint64_t planned = std::max<std::uint64_t>(planned_.load(), 1);
  if (options_.time_limit > 0) {
    const double f_samples = double(now_done) / double(planned);
    const double f_time = std::chrono::duration<double>(Clock::now() - start_).count() / options_.time_limit;
    options_.progress(long(std::min(1.0, std::max(f_samples, f_time)) * 1e6), 1000000);
  } else {
    options_.progress(long(now_done), long(planned));
  }
}

RenderStats RenderJob::stats() const {
  RenderStats s;
  s.rays = counters_;
  s.seconds = seconds_;
  s.cancelled = cancelled_.load();
  s.time_limited = out_of_time_.load();
  s.samples = done_.load();
  s.passes = passes_.load();
  s.replayed_tiles = replayed_.load();
  return s;
}

}  // namespace strahl
