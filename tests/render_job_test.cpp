// The render job (render/render_job.h): the film's sums — not only the rounded image — are the
// same for every pass plan, tile size, thread count and back end, including a back end that
// renders the tiles of a pass away from the film in any order and one that hands a tile out
// again (an MPI master after losing a worker); and a cancel or the time limit ends a render
// within a fraction of a second even when one pixel alone would take minutes.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>

#include "strahl/render/cpu_backend.h"
#include "strahl/render/render_job.h"
#include "strahl/render/tile_renderer.h"
#include "strahl/scene/scene_file.h"
#include "job_result.h"
#include "test_helpers.h"

namespace strahl::render_job_test {
namespace {

RenderScene whitted(SamplerKind kind, int spp, FilterKind filter = FilterKind::Box, Real radius = 0.5,
                    int width = 40, int height = 24) {
  Scene scene = load_scene(fs::path(STRAHL_SOURCE_DIR) / "scenes" / "lecture-whitted.yaml");
  scene.settings.width = width;
  scene.settings.height = height;
  SamplingSettings& s = scene.settings.sampling;
  s.sampler = kind;
  s.spp = spp;
  s.seed = 5;
  s.filter = {filter, radius};
  s.adaptive_min = 2;
  return compile(scene);
}

// A back end away from the film: takes every tile of the pass first, renders them last to first
// with a FilmLayout of its own, then hands them back.
class RemoteBackend final : public TileBackend {
 public:
  bool hand_out_again = false;  // throw the first tile away and ask the job for it anew
  void render_pass(RenderJob& job) override {
    std::vector<TileWork> taken;
    while (std::optional<TileWork> w = job.next_tile()) taken.push_back(std::move(*w));
    if (hand_out_again && !taken.empty()) taken.front() = job.tile(taken.front().index);
    const FilmLayout layout = job.film_layout();
    std::reverse(taken.begin(), taken.end());
    for (TileWork& w : taken) {
      render_tile(job.view(), job.sampler(), layout, job.stop(), w);
      job.deliver(std::move(w));
    }
  }
};

using Result = test::JobResult;
Result run(const RenderScene& rs, TileBackend& backend, JobOptions options) { return test::run_job(rs, backend, options); }

JobOptions tiles(int size, bool progressive = false, std::uint32_t max_pass = 0) {
  JobOptions o;
  o.tile_size = size;
  o.progressive = progressive;
  o.max_pass_samples = max_pass;
  return o;
}

TEST(RenderJob, FilmSumsAreTheSameForEveryPassPlanTileSizeAndBackEnd) {
  for (const RenderScene& rs :
       {whitted(SamplerKind::Sobol, 8), whitted(SamplerKind::Grid, 9),
        whitted(SamplerKind::Stratified, 4, FilterKind::Mitchell, 2), whitted(SamplerKind::Adaptive, 16)}) {
    CpuBackend one_thread(1), two_threads(2);
    const Result reference = run(rs, one_thread, tiles(32));
    RemoteBackend remote, remote_again;
    remote_again.hand_out_again = true;
    const Result results[] = {run(rs, two_threads, tiles(7)),
                              run(rs, two_threads, tiles(5, true)),         // passes of 1, 1, 2, 4
                              run(rs, one_thread, tiles(16, true, 1)),      // a pass per sample
                              run(rs, remote, tiles(9, true, 3)),           // away from the film, backwards
                              run(rs, remote_again, tiles(11, true))};      // a tile handed out twice
    for (const Result& r : results) {
      EXPECT_EQ(r.stats.samples, reference.stats.samples) << sampler_name(rs.sampling.sampler);
      EXPECT_EQ(r.pixel_samples, reference.pixel_samples) << sampler_name(rs.sampling.sampler);
      EXPECT_EQ(r.stats.rays.total(), reference.stats.rays.total()) << sampler_name(rs.sampling.sampler);
      std::size_t differ = 0;
      for (std::size_t i = 0; i < r.sums.size(); ++i) differ += r.sums[i] != reference.sums[i];
      EXPECT_EQ(differ, 0u) << sampler_name(rs.sampling.sampler) << ": pixels whose sums differ";
    }
  }
}

TEST(RenderJob, PassPlansFollowTheOptions) {
  const RenderScene rs = whitted(SamplerKind::Sobol, 8);
  CpuBackend cpu(2);
  EXPECT_EQ(run(rs, cpu, tiles(16)).stats.passes, 1);
  EXPECT_EQ(run(rs, cpu, tiles(16, true)).stats.passes, 4);     // 1, 1, 2, 4
  EXPECT_EQ(run(rs, cpu, tiles(16, true, 1)).stats.passes, 8);  // 1 × 8
  EXPECT_EQ(run(rs, cpu, tiles(16, true, 3)).stats.passes, 5);  // 1, 1, 2, 3, 1
}

// One pixel of a million samples: far more than a second of work.
RenderScene one_expensive_pixel() { return whitted(SamplerKind::Random, 1 << 20, FilterKind::Box, 0.5, 1, 1); }

TEST(RenderJob, CancelStopsWithinOnePixel) {
  const RenderScene rs = one_expensive_pixel();
  RenderJob job(rs.view(), rs.sampling);
  CpuBackend cpu(1);
  std::thread canceller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    job.cancel();
  });
  const auto start = std::chrono::steady_clock::now();
  job.run(cpu);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  canceller.join();
  const RenderStats stats = job.stats();
  EXPECT_TRUE(stats.cancelled);
  EXPECT_FALSE(stats.time_limited);
  EXPECT_GT(stats.samples, 0u);
  EXPECT_LT(stats.samples, 1u << 20);
  EXPECT_EQ(job.pixel_samples()[0], stats.samples);
  EXPECT_LT(seconds, 1.0) << "the cancel took effect only after " << seconds << " s";
  EXPECT_GT(job.image().at(0, 0).r + job.image().at(0, 0).g + job.image().at(0, 0).b, 0) << "the samples taken count";
}

TEST(RenderJob, TimeLimitStopsWithinOnePixel) {
  const RenderScene rs = one_expensive_pixel();
  JobOptions o;
  o.time_limit = 0.1;
  RenderJob job(rs.view(), rs.sampling, o);
  CpuBackend cpu(1);
  const auto start = std::chrono::steady_clock::now();
  job.run(cpu);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(job.stats().time_limited);
  EXPECT_FALSE(job.stats().cancelled);
  EXPECT_LT(seconds, 1.0);
  EXPECT_LT(job.stats().samples, 1u << 20);
}

TEST(RenderJob, ExternalFlagStopsTheRender) {
  const RenderScene rs = one_expensive_pixel();
  std::atomic<bool> flag{false};
  JobOptions o;
  o.cancel = &flag;
  RenderJob job(rs.view(), rs.sampling, o);
  CpuBackend cpu(2);
  std::thread signaller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    flag = true;
  });
  job.run(cpu);
  signaller.join();
  EXPECT_TRUE(job.stats().cancelled);
  EXPECT_LT(job.stats().samples, 1u << 20);
}

}  // namespace
}  // namespace strahl::render_job_test
