// The CUDA back end without a GPU (cuda/flat_pass.h, cuda/flat_pass_job.h): its passes run on the
// host — every tile of a pass flattened into per-pixel arrays, render_flat_pixel() (what each
// thread of the kernel runs) over the pixels in an order unlike the CPU's, the wide filter's
// fixed-point sums added as the kernel's atomics add them, the ray counters summed through the
// kernel's counter array — and the film's sums, sample counts and ray counts must equal the CPU
// back end's bit for bit, for every sampler, pixel-local and wide filters, adaptive passes, and a
// pass stopped or failed in the middle. Only the CUDA calls (uploads, launch, copies) and the
// device's arithmetic are left to tools/gpu-check.sh on a GPU.

#include <gtest/gtest.h>

#include <array>
#include <functional>

#include "strahl/cuda/flat_pass_job.h"
#include "strahl/render/cpu_backend.h"
#include "strahl/render/render_job.h"
#include "strahl/scene/scene_file.h"
#include "job_result.h"
#include "test_helpers.h"

namespace strahl::flat_pass_test {
namespace {

// A flat pass on the host: the pixels (the kernel's threads) in a scrambled order, each
// thread's counters summed through counter_array() as the kernel's warps sum them.
class HostFlatBackend final : public TileBackend {
 public:
  // Cancels the job after this many pixels of its first pass (−1: never); the remaining pixels
  // then see the stop flag set, as the kernel's threads do once the host sets it.
  long cancel_after = -1;
  bool fail = false;  // the pass fails (a kernel fault): nothing is rendered
  int passes = 0;

  void render_pass(RenderJob& job) override {
    ++passes;
    render_flat_pass(job, [&](const FilmParams& film, PassData& pass, RayCounters& counters) {
      if (fail) return false;
      volatile int stop = 0;
      const PassArgs a = host_pass_args(job.view(), job.sampler(), film, pass, &stop);
      unsigned long long sums[kPassCounters] = {};
      for (std::uint32_t k = 0; k < a.n; ++k) {
        if (passes == 1 && long(k) == cancel_after) job.cancel();
        if (job.stop().requested()) stop = 1;
        const std::uint32_t i = scrambled(k, a.n);
        RayCounters c;
        render_flat_pixel(a, i, c, [](std::int64_t* q, std::int64_t v) { *q += v; });
        unsigned long long v[kPassCounters];
        counter_array(c, v);
        for (int j = 0; j < kPassCounters; ++j) sums[j] += v[j];
      }
      add_counter_array(counters, sums);
      return true;
    });
  }

 private:
  // Every pixel once: the odd-numbered ones backwards, then the even ones.
  static std::uint32_t scrambled(std::uint32_t k, std::uint32_t n) {
    const std::uint32_t odd = n / 2;
    return k < odd ? 2 * (odd - 1 - k) + 1 : 2 * (k - odd);
  }
};

RenderScene scene(const char* file, SamplerKind kind, int spp, FilterKind filter = FilterKind::Box,
                  Real radius = 0.5, const std::function<void(Scene&)>& edit = {}) {
  Scene sc = load_scene(fs::path(STRAHL_SOURCE_DIR) / "scenes" / file);
  sc.settings.width = 40;
  sc.settings.height = 24;
  SamplingSettings& s = sc.settings.sampling;
  s.sampler = kind;
  s.spp = spp;
  s.seed = 3;
  s.filter = {filter, radius};
  s.adaptive_min = 2;
  if (edit) edit(sc);
  return compile(sc);
}

using Result = test::JobResult;
Result run(const RenderScene& rs, TileBackend& backend, int tile_size, bool progressive = false) {
  JobOptions o;
  o.tile_size = tile_size;
  o.progressive = progressive;
  return test::run_job(rs, backend, o);
}

void expect_equal(const Result& flat, const Result& cpu, const std::string& what) {
  EXPECT_EQ(flat.stats.samples, cpu.stats.samples) << what;
  EXPECT_EQ(flat.pixel_samples, cpu.pixel_samples) << what;
  EXPECT_EQ(flat.stats.rays.camera, cpu.stats.rays.camera) << what;
  EXPECT_EQ(flat.stats.rays.shadow, cpu.stats.rays.shadow) << what;
  EXPECT_EQ(flat.stats.rays.reflection, cpu.stats.rays.reflection) << what;
  EXPECT_EQ(flat.stats.rays.refraction, cpu.stats.rays.refraction) << what;
  EXPECT_EQ(flat.stats.rays.invalid_samples, cpu.stats.rays.invalid_samples) << what;
  EXPECT_EQ(flat.stats.rays.cut, cpu.stats.rays.cut) << what;
  std::size_t differ = 0;
  for (std::size_t i = 0; i < flat.sums.size(); ++i) differ += flat.sums[i] != cpu.sums[i];
  EXPECT_EQ(differ, 0u) << what << ": pixels whose film sums differ";
}

TEST(FlatPass, EqualsTheCpuBackEndBitForBit) {
  const auto budget = [](Scene& s) { s.settings.ray_budget = 2; };  // cuts rays: RayCounters::cut
  const struct {
    const char* name;
    RenderScene rs;
  } cases[] = {
      {"whitted grid 1", scene("lecture-whitted.yaml", SamplerKind::Grid, 1)},
      {"whitted grid 9", scene("lecture-whitted.yaml", SamplerKind::Grid, 9)},
      {"whitted sobol 8", scene("lecture-whitted.yaml", SamplerKind::Sobol, 8)},
      {"whitted stratified 4, mitchell 2", scene("lecture-whitted.yaml", SamplerKind::Stratified, 4,
                                                 FilterKind::Mitchell, 2)},
      {"whitted adaptive 16", scene("lecture-whitted.yaml", SamplerKind::Adaptive, 16)},
      {"distributed random 4, gaussian 1.5", scene("lecture-distributed.yaml", SamplerKind::Random, 4,
                                                   FilterKind::Gaussian, 1.5)},
      {"motion blur stratified 4", scene("motion-blur.yaml", SamplerKind::Stratified, 4)},
      {"refraction, a ray budget of 2", scene("refraction.yaml", SamplerKind::Grid, 4, FilterKind::Box, 0.5, budget)},
  };
  for (const auto& c : cases) {
    CpuBackend cpu(2);
    const Result reference = run(c.rs, cpu, 16);
    HostFlatBackend flat;
    expect_equal(run(c.rs, flat, 7), reference, c.name);
    HostFlatBackend progressive;
    expect_equal(run(c.rs, progressive, 9, true), reference, std::string(c.name) + ", progressive");
    EXPECT_GT(progressive.passes, c.rs.sampling.spp > 1 ? 1 : 0) << c.name;
  }
  // The checks above see every counter: the budget case cuts rays.
  CpuBackend cpu(1);
  EXPECT_GT(run(cases[7].rs, cpu, 16).stats.rays.cut, 0u);
}

// A stop in the middle of a launch: the pixels whose threads ran before it keep all their samples
// (the film's sums equal the full render's), the others none; the job reports the cancel.
TEST(FlatPass, StopInTheMiddleKeepsWhatWasTaken) {
  const RenderScene rs = scene("lecture-whitted.yaml", SamplerKind::Sobol, 4);
  CpuBackend cpu(2);
  const Result full = run(rs, cpu, 8);
  HostFlatBackend flat;
  flat.cancel_after = 300;  // of 960 pixels
  const Result r = run(rs, flat, 8);
  EXPECT_TRUE(r.stats.cancelled);
  EXPECT_EQ(r.stats.samples, 300u * 4);
  std::size_t complete = 0, empty = 0, differ = 0;
  for (std::size_t i = 0; i < r.sums.size(); ++i) {
    if (r.pixel_samples[i] == 4) {
      ++complete;
      differ += r.sums[i] != full.sums[i];
    } else {
      empty += r.pixel_samples[i] == 0;
    }
  }
  EXPECT_EQ(complete, 300u);
  EXPECT_EQ(empty, r.sums.size() - 300);
  EXPECT_EQ(differ, 0u);
}

// A pass that fails (a kernel fault, out of memory) renders nothing and ends the job.
TEST(FlatPass, AFailedPassEndsTheJobWithNothingTaken) {
  const RenderScene rs = scene("lecture-whitted.yaml", SamplerKind::Sobol, 4);
  HostFlatBackend flat;
  flat.fail = true;
  const Result r = run(rs, flat, 8, true);
  EXPECT_EQ(flat.passes, 1);
  EXPECT_TRUE(r.stats.cancelled);
  EXPECT_EQ(r.stats.samples, 0u);
  for (std::uint32_t n : r.pixel_samples) EXPECT_EQ(n, 0u);
}

}  // namespace
}  // namespace strahl::flat_pass_test
