#pragma once
// One render, whoever asks for it and whatever renders it (DESIGN.md, "One render job"): the job
// plans passes, hands out the tiles of each pass, takes the rendered tiles back into its film,
// reports progress, writes checkpoints, and stops on cancel or at the time limit. Front ends —
// the CLI, the viewer, the MPI master, Python — create a job and run it; back ends
// (TileBackend: CPU threads here, MPI ranks and the GPU elsewhere) only render the tiles they
// take with next_tile() and hand back with deliver().
//
// Passes: without adaptive sampling, a time limit, checkpoints or `progressive`, one pass takes
// every sample. Otherwise passes double each pixel's count (1, 1, 2, 4, … up to spp); adaptive
// sampling starts with its minimum and then doubles where render/adaptive.h says so. With
// `max_pass_samples`, each of those passes is split into passes of at most that many samples (the
// viewer's 1 sample per pixel per frame); adaptive decisions still follow the whole pass. The film continues each pixel's sums across passes (tile.h),
// so the image is the same for any pass plan, tile size, thread count or back end.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include "strahl/image/image.h"
#include "strahl/render/film.h"
#include "strahl/render/ray_counters.h"
#include "strahl/render/scene_view.h"
#include "strahl/util/zeroed_array.h"
#include "strahl/render/stop_token.h"
#include "strahl/render/tile.h"
#include "strahl/sampling/pixel_sampler.h"

namespace strahl {

class AdaptivePlanner;

// Called with (samples done, samples in all) after each delivered tile, from whichever thread
// delivered it; must be thread-safe. With a time limit the units are millionths of the whole
// (the larger of the fraction of samples and the fraction of the time used).
using ProgressCallback = std::function<void(long done, long total)>;

struct JobOptions {
  int tile_size = 32;  // pixels along a tile's side
  // When set and it becomes true (a signal handler), rendering stops between two samples; the
  // image keeps every sample taken, each pixel weighted by its own count.
  const std::atomic<bool>* cancel = nullptr;
  double time_limit = 0;  // seconds, 0: none; stops as cancel does
  // Called with the image so far every `checkpoint_interval` seconds (0: never), from a thread
  // delivering a tile, one call at a time.
  double checkpoint_interval = 0;
  std::function<void(const Image&)> checkpoint{};
  ProgressCallback progress{};
  // Called with every tile delivered (complete, or stopped early: see TileWork::taken) from the
  // delivering thread, one call at a time — the resume journal (render/journal.h) records them.
  std::function<void(const TileWork&)> on_tile{};
  // Tiles an earlier run of the same render already delivered (the resume journal): a tile of the
  // current pass found here is delivered as it is instead of being handed out.
  std::function<std::optional<TileWork>(int pass, int index)> replay{};
  bool progressive = false;           // passes even without adaptive sampling, time limit or checkpoints
  std::uint32_t max_pass_samples = 0;  // at most this many samples per pixel and pass (0: no bound)
};

struct RenderStats {
  RayCounters rays;
  double seconds = 0;
  bool cancelled = false;     // stopped by the cancel flag or cancel() before the last sample
  bool time_limited = false;  // stopped by the time limit
  std::uint64_t samples = 0;  // camera samples taken (replayed tiles' included)
  std::uint64_t replayed_tiles = 0;  // tiles taken from JobOptions::replay instead of rendered
  int passes = 0;
};

class RenderJob;

// The film layout a job over (view, sampling) uses: what a back end away from the job (an MPI
// worker) makes for itself.
FilmLayout film_layout_for(const SceneView& view, const SamplingSettings& sampling);

// A back end: renders the tiles of the job's current pass. render_pass takes tiles with
// job.next_tile() until it returns none, renders each (the samples it asks for, stopping early
// when job.stop() is requested), and hands every tile it took back with job.deliver(), before it
// returns.
class TileBackend {
 public:
  virtual ~TileBackend() = default;
  virtual void render_pass(RenderJob& job) = 0;
};

class RenderJob {
 public:
  // `view` is copied (plain pointers into a RenderScene, which must outlive the job); a front
  // end may change its camera (the viewer's reduced resolution) before handing it over.
  RenderJob(const SceneView& view, const SamplingSettings& sampling, JobOptions options = {});
  RenderJob(const RenderJob&) = delete;
  RenderJob& operator=(const RenderJob&) = delete;
  ~RenderJob();

  // Renders pass after pass with `backend` until every sample is taken or the job is stopped.
  // Call once.
  void run(TileBackend& backend);
  // Stops the job from any thread (the viewer moving on): rendering ends within one sample.
  void cancel();

  // ---- for back ends (thread-safe) ----
  const SceneView& view() const { return view_; }
  const PixelSampler& sampler() const { return sampler_; }
  const FilmLayout& film_layout() const { return film_.layout(); }
  const StopToken& stop() const { return stop_; }
  // The next tile of the current pass, the film's sums carried in; none when every tile of the
  // pass has been handed out or the job is stopping.
  std::optional<TileWork> next_tile();
  // The same into `work`, reusing its buffers (a back end's thread renders tile after tile in
  // one TileWork: no allocation per tile); false when none is left.
  bool next_tile(TileWork& work);
  // Takes a rendered tile back into the film (reads it only: the caller may reuse it).
  void deliver(const TileWork& work);
  int tile_count() const { return tiles_x_ * tiles_y_; }
  // The tile of the current pass with this index (for a back end that must hand one out again,
  // e.g. after losing an MPI worker); the film's state is carried in afresh.
  TileWork tile(int index) const;
  void tile(int index, TileWork& work) const;  // the same into `work`, reusing its buffers

  // ---- for front ends (thread-safe) ----
  Image image() const { return film_.resolve(); }  // the image so far
  const Film& film() const { return film_; }
  std::uint64_t samples_done() const { return done_.load(std::memory_order_relaxed); }
  std::uint64_t samples_planned() const { return planned_.load(std::memory_order_relaxed); }
  int passes_done() const { return passes_.load(std::memory_order_relaxed); }
  // After run().
  RenderStats stats() const;
  // Samples per pixel taken, row-major from the top (the job's own array: no copy of it).
  std::span<const std::uint32_t> pixel_samples() const { return {counts_.data(), counts_.size()}; }

 private:
  using Clock = std::chrono::steady_clock;

  bool plan_next_pass();  // false: nothing left to do
  bool take_pass();       // the next pass from pending_, at most max_pass_samples each; false: none
  bool replayable(const TileWork& done, int index) const;
  void report(std::uint64_t now_done);

  SceneView view_;
  SamplingSettings sampling_;
  PixelSampler sampler_;
  JobOptions options_;
  Film film_;
  std::unique_ptr<AdaptivePlanner> planner_;  // render/adaptive.h (adaptive sampling only)
  int width_ = 0, height_ = 0, tile_ = 1, tiles_x_ = 0, tiles_y_ = 0;
  std::uint32_t max_spp_ = 1;
  bool adaptive_ = false, progressive_ = false;

  StopToken stop_;
  std::atomic<bool> out_of_time_{false}, cancelled_{false};
  ZeroedArray<std::uint32_t> counts_;  // samples per pixel taken so far (row-major from the top)
  // Dense passes (sparse_ false) give every pixel the same: dense_taken_ samples before the
  // current pass, dense_add_ in it, dense_pending_ still to take in the planned pass when
  // max_pass_samples splits it (the adaptive decisions are taken only after the whole of it, so
  // the split leaves the image alone). A pass starts only when the one before it is complete.
  std::uint32_t dense_taken_ = 0, dense_add_ = 0, dense_pending_ = 0;
  // Adaptive passes after the first are sparse, per pixel: add_ the samples of the current pass,
  // pending_ those still to take in the planned pass; the pixels with pending_ > 0, the pixels
  // with add_ > 0, and which tiles have any of those (busy_), so that a pass costs what its
  // samples cost, not a walk over the whole image.
  bool sparse_ = false;
  ZeroedArray<std::uint32_t> add_;
  std::vector<std::uint32_t> pending_;
  std::vector<std::uint32_t> pending_pixels_, pass_pixels_;
  std::vector<std::uint8_t> busy_;
  int pass_ = 0;
  std::atomic<int> next_{0};  // next tile of the current pass to hand out
  std::atomic<std::uint64_t> done_{0}, planned_{0};
  std::atomic<int> passes_{0};

  std::mutex deliver_mutex_;  // guards counters_
  RayCounters counters_;
  std::mutex checkpoint_mutex_;  // guards next_checkpoint_; one checkpoint at a time
  std::mutex on_tile_mutex_;     // one on_tile call at a time
  std::atomic<std::uint64_t> replayed_{0};
  Clock::time_point start_{}, next_checkpoint_{};
  double seconds_ = 0;
};

}  // namespace strahl
