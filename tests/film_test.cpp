// The film and the render loop: images independent of threads and tile size for every sampler
// and filter; filters keep a flat image flat; progressive passes equal one pass; adaptive sampling
// spends its samples on edges and beats stratified sampling there; time limits, checkpoints and
// AOVs.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "strahl/image/metrics.h"
#include "strahl/render/adaptive.h"
#include "strahl/render/aov.h"
#include "strahl/render/cpu_backend.h"
#include "strahl/render/film_sample.h"
#include "strahl/render/render_job.h"
#include "strahl/scene/scene_file.h"
#include "test_helpers.h"

namespace strahl::film_test {
namespace {

// The image, and where given the render's statistics and samples per pixel.
Image render_with(const RenderScene& rs, int threads, int tile, RenderStats* stats = nullptr,
                  std::vector<std::uint32_t>* pixel_samples = nullptr) {
  JobOptions o;
  o.tile_size = tile;
  RenderJob job(rs.view(), rs.sampling, o);
  CpuBackend cpu(threads);
  job.run(cpu);
  if (stats) *stats = job.stats();
  if (pixel_samples) pixel_samples->assign(job.pixel_samples().begin(), job.pixel_samples().end());
  return job.image();
}

SamplingSettings sampling(SamplerKind kind, int spp, FilterKind filter = FilterKind::Box, Real radius = 0.5) {
  SamplingSettings s;
  s.sampler = kind;
  s.spp = spp;
  s.seed = 11;
  s.filter = {filter, radius};
  s.adaptive_min = 2;
  return s;
}

RenderScene whitted(const SamplingSettings& s) {
  Scene scene = load_scene(fs::path(STRAHL_SOURCE_DIR) / "scenes" / "lecture-whitted.yaml");
  scene.settings.width = 40;
  scene.settings.height = 24;
  scene.settings.sampling = s;
  return compile(scene);
}

TEST(Film, EverySamplerAndFilterIsIndependentOfThreadsAndTiles) {
  for (const SamplingSettings& s :
       {sampling(SamplerKind::Grid, 4), sampling(SamplerKind::Stratified, 4, FilterKind::Gaussian, 1.5),
        sampling(SamplerKind::Random, 4, FilterKind::Mitchell, 2), sampling(SamplerKind::Sobol, 4, FilterKind::Tent, 1),
        sampling(SamplerKind::Adaptive, 8, FilterKind::Mitchell, 2)}) {
    const RenderScene rs = whitted(s);
    RenderStats ref_stats;
    std::vector<std::uint32_t> ref_pixel_samples;
    const Image reference = render_with(rs, 1, 32, &ref_stats, &ref_pixel_samples);
    for (const auto& [threads, tile] : {std::pair{2, 7}, std::pair{2, 1}, std::pair{0, 16}}) {
      RenderStats stats;
      std::vector<std::uint32_t> pixel_samples;
      const Image img = render_with(rs, threads, tile, &stats, &pixel_samples);
      EXPECT_TRUE(img == reference) << sampler_name(s.sampler) << " " << filter_name(s.filter.kind) << ", " << threads
                                    << " threads, tile " << tile << ": max difference "
                                    << test::max_abs_diff(img, reference);
      EXPECT_EQ(stats.samples, ref_stats.samples);
      EXPECT_EQ(pixel_samples, ref_pixel_samples);
    }
  }
}

// With the pixel-local box filter the film equals render_pixel() (samples 0 … spp−1 averaged)
// bit for bit, for every sampler; seeds change stochastic samplers' images.
TEST(Film, PixelLocalFilterEqualsRenderPixel) {
  for (const SamplerKind kind : {SamplerKind::Stratified, SamplerKind::Random, SamplerKind::Sobol}) {
    const RenderScene rs = whitted(sampling(kind, 4));
    const Image img = render_with(rs, 2, 5);
    RayCounters counters;
    for (int row = 0; row < img.height(); ++row)
      for (int x = 0; x < img.width(); ++x) {
        const Vec3 c = render_pixel(rs.view(), x, row, rs.sampling, counters);
        ASSERT_TRUE(img.at(x, row) == (Rgb{float(c.x), float(c.y), float(c.z)})) << sampler_name(kind) << " " << x;
      }
    SamplingSettings other = rs.sampling;
    other.seed = 12;
    EXPECT_FALSE(render_with(whitted(other), 2, 5) == img) << sampler_name(kind);
  }
}

// An emitter filling the view: every filter, negative lobes included, reproduces its colour.
TEST(Film, FiltersKeepAFlatImageFlat) {
  const Vec3 colour(0.25, 0.5, 0.75);
  for (const FilterKind kind : {FilterKind::Box, FilterKind::Tent, FilterKind::Gaussian, FilterKind::Mitchell})
    for (const Real radius : {Real(0.5), Real(1.5), Real(4)}) {
      // Mitchell at radius 0.5 has its negative lobes inside the pixel: sparse weights can sum to ~0.
      if (kind == FilterKind::Mitchell && radius < 1) continue;
      Scene s;
      s.add(Plane({0, 0, 1}, -2, test::emissive_like(colour)));
      test::set_camera(s, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, -1, 1, -1, 1, 1, 12, 9);
      s.settings.sampling = sampling(SamplerKind::Stratified, 4, kind, radius);
      const Image img = test::render_image(s, 2, 5);
      for (const Rgb& p : img.pixels())
        ASSERT_TRUE(test::vec_near(test::to_vec(p), colour, 1e-6)) << filter_name(kind) << " r " << radius;
    }
}

// film_to_fixed4 (four values in one AVX vector where the build has AVX2) is film_to_fixed
// (llround) value for value: halves away from zero at every scale, the doubles either side of a
// half, the largest double below 1/2 (where adding 1/2 would round up), the clamps, NaN.
TEST(Film, FixedPointOfFourIsTheScalarConversion) {
  std::vector<double> v = {0.0, -0.0, 1e6, -1e6, 2e6, -2e6, kInfinity, -kInfinity,
                           std::numeric_limits<double>::quiet_NaN(), 0.49999999999999994 / kFilmFixedScale,
                           -0.49999999999999994 / kFilmFixedScale, 1e-300, -1e-300};
  for (double scale = 1; scale < 1e15; scale *= 3.7)
    for (const double half : {0.5, 1.5, 2.5, 7.5}) {
      const double x = (std::floor(scale) + half) / kFilmFixedScale;  // exactly a half on the grid
      for (const double y : {x, std::nextafter(x, 0.0), std::nextafter(x, 1e300)}) {
        v.push_back(y);
        v.push_back(-y);
      }
    }
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 20000; ++i) v.push_back(u(rng) * std::pow(10.0, 7 * u(rng)));
  while (v.size() % 4 != 0) v.push_back(0.5);
  int halves = 0;
  for (std::size_t i = 0; i < v.size(); i += 4) {
    std::int64_t q[4];
    film_to_fixed4(&v[i], q);
    for (int k = 0; k < 4; ++k) {
      const double x = v[i + std::size_t(k)];
      ASSERT_EQ(q[k], film_to_fixed(x)) << std::hexfloat << x;
      if (std::fabs(x) * kFilmFixedScale - std::floor(std::fabs(x) * kFilmFixedScale) == 0.5) ++halves;
    }
  }
  EXPECT_GT(halves, 100);  // the halves above are really halves
}

// A white emitting sphere on black: its silhouette is the only edge.
Scene edge_scene(int n) {
  Scene s;
  s.add(Sphere({0.1, 0.05, -3}, 1, test::emissive_like(Vec3(1))));
  test::set_camera(s, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, -0.5, 0.5, -0.5, 0.5, 1, n, n);
  return s;
}

TEST(Adaptive, SpendsSamplesOnEdgesAndBeatsStratifiedAtTheSameCount) {
  constexpr int n = 32;
  Scene s = edge_scene(n);
  s.settings.sampling = sampling(SamplerKind::Stratified, 1024);
  const Image reference = test::render_image(s, 0);

  s.settings.sampling = sampling(SamplerKind::Adaptive, 256);
  s.settings.sampling.adaptive_min = 4;
  s.settings.sampling.adaptive_threshold = 0.02;
  RenderStats stats;
  std::vector<std::uint32_t> pixel_samples;
  const Image adaptive = render_with(compile(s), 0, 32, &stats, &pixel_samples);
  // Edge pixels (reference strictly between black and white) against flat ones.
  double edge_samples = 0, flat_samples = 0;
  int edges = 0, flats = 0, flats_at_minimum = 0;
  for (int row = 0; row < n; ++row)
    for (int x = 0; x < n; ++x) {
      const float v = reference.at(x, row).r;
      const double c = pixel_samples[std::size_t(row * n + x)];
      if (v > 0.02f && v < 0.98f) {
        edge_samples += c;
        ++edges;
      } else if (v == 0 || v == 1) {
        flat_samples += c;
        ++flats;
        flats_at_minimum += c == 4;
      }
    }
  std::uint32_t most = 0;
  for (std::uint32_t c : pixel_samples) most = std::max(most, c);
  EXPECT_LE(most, 256u);
  ASSERT_GT(edges, 20);
  ASSERT_GT(flats, 200);
  // Flat pixels next to an edge refine too (the neighbour rule); most flat pixels stop at the minimum.
  EXPECT_GT(edge_samples / edges, 4 * (flat_samples / flats)) << "mean samples on edges vs flat pixels";
  EXPECT_GT(flats_at_minimum, flats / 2);
  const double average = double(stats.samples) / (n * n);
  EXPECT_LT(average, 128);

  // Stratified with at least as many samples per pixel.
  const int side = int(std::ceil(std::sqrt(average)));
  s.settings.sampling = sampling(SamplerKind::Stratified, side * side);
  const Image stratified = test::render_image(s, 0);
  const double e_adaptive = rmse(adaptive, reference), e_stratified = rmse(stratified, reference);
  EXPECT_LT(e_adaptive, e_stratified) << "adaptive " << average << " spp vs stratified " << side * side << " spp";
}

TEST(Adaptive, RelativeErrorIsTheStandardErrorOverTheMean) {
  PixelStats p;
  for (const double v : {0.5, 1.5, 0.5, 1.5}) {
    p.sum += v;
    p.sum_sq += v * v;
    ++p.n;
  }
  // mean 1, sample variance 1/3, standard error sqrt(1/12).
  EXPECT_NEAR(relative_error(p), std::sqrt(1.0 / 12), 1e-12);
  EXPECT_EQ(relative_error(PixelStats{0, 0, 8}), 0) << "black pixels are converged";
  EXPECT_TRUE(std::isinf(relative_error(PixelStats{1, 1, 1})));
}

// A synthetic film for the planner: pixel (x, row)'s sample s sees a disc of radius 7 (0.8 inside,
// 0.1 outside, at a jittered position within the pixel) and, left of x = 6, noise of ±0.05.
struct SyntheticFilm {
  int w, h;
  Film film;
  std::vector<std::uint32_t> counts;
  bool second_disc = false;                                 // and a shaded disc on the left
  std::function<double(int, int, std::uint32_t)> value;  // replaces all that when set
  SyntheticFilm(int w_, int h_) : w(w_), h(h_), film(w_, h_, Filter{}), counts(std::size_t(w_) * std::size_t(h_), 0) {}
  static double jitter(std::uint64_t k) {
    k = (k ^ (k >> 31)) * 0x7fb5d329728ea185ull;
    k = (k ^ (k >> 27)) * 0x81dadef4bc2dd44dull;
    return double(k >> 11) * 0x1.0p-53;
  }
  void take(const std::vector<std::uint32_t>& add) {
    TileWork t;
    t.rect = {0, 0, w, h};
    film.begin_tile(t);
    for (int row = 0; row < h; ++row)
      for (int x = 0; x < w; ++x) {
        const std::size_t p = std::size_t(row) * std::size_t(w) + std::size_t(x);
        for (std::uint32_t k = 0; k < add[p]; ++k) {
          const std::uint64_t key = (p << 20) + counts[p] + k;
          const double fx = x + jitter(3 * key), fy = row + jitter(3 * key + 1);
          double v = std::hypot(fx - 0.6 * w, fy - 0.5 * h) < 7 ? 0.8 : 0.1;
          if (second_disc && std::hypot(fx - 0.2 * w, fy - 0.7 * h) < 0.2 * h) v = 0.1 + 0.04 * std::sin(fx * fy);
          if (value) v = value(x, row, counts[p] + k);
          if (x < 6) v += 0.1 * (jitter(3 * key + 2) - 0.5);
          film.layout().add_sample(t, x, row, CameraSample{}, Vec3(Real(v)));
        }
        t.taken[p] = add[p];
        counts[p] += add[p];
      }
    film.merge(t);
  }
};

// With one sample a pixel's error is its largest relative contrast to a neighbour with samples.
TEST(Adaptive, OneSampleUsesTheContrastToItsNeighbours) {
  SyntheticFilm f(40, 24);
  std::vector<std::uint32_t> add(f.counts.size(), 1), next(f.counts.size(), 0);
  f.take(add);
  const auto mean = [&](int x, int row) { return f.film.stats(x, row).sum / f.film.stats(x, row).n; };
  double e = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) e = std::max(e, std::abs(mean(20, 12) - mean(20 + dx, 12 + dy)));
  EXPECT_EQ(contrast_error(f.film, 20, 12), e / std::max(mean(20, 12), 0.01));
  EXPECT_EQ(pixel_error(f.film, 20, 12), contrast_error(f.film, 20, 12));
  // Flat pixels far from the disc and the noise stop at one sample; the disc's rim refines.
  AdaptivePlanner planner;
  planner.plan(f.film, f.counts, 16, 0.3, next);
  int rim = 0;
  for (int row = 0; row < f.h; ++row)
    for (int x = 0; x < f.w; ++x) {
      const double r = std::hypot(x + 0.5 - 0.6 * f.w, row + 0.5 - 0.5 * f.h);
      const std::uint32_t a = next[std::size_t(row) * std::size_t(f.w) + std::size_t(x)];
      if (x >= 8 && (r < 3 || r > 11)) {
        EXPECT_EQ(a, 0u) << x << ", " << row;
      }
      rim += a > 0 && r > 5.5 && r < 8.5;
    }
  EXPECT_GT(rim, 30);
}

// Pass by pass, the planner's incremental plan equals examining every pixel.
TEST(AdaptivePlanner, IncrementalPlanEqualsAFullPlan) {
  for (const std::uint32_t min : {1u, 4u})
    for (const double threshold : {0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 1.0}) {
      SyntheticFilm f(97, 61);
      f.second_disc = true;
      std::vector<std::uint32_t> add(f.counts.size(), min), full(f.counts.size(), 0);
      AdaptivePlanner incremental, every_pixel;
      int passes = 0;
      for (;;) {
        f.take(add);
        const std::uint64_t a = incremental.plan(f.film, f.counts, 64, threshold, add);
        const std::uint64_t b = every_pixel.plan(f.film, f.counts, 64, threshold, full, true);
        ASSERT_EQ(a, b) << "min " << min << " threshold " << threshold << " pass " << passes;
        ASSERT_EQ(add, full) << "min " << min << " threshold " << threshold << " pass " << passes;
        std::vector<std::uint32_t> planned = incremental.planned(), want;
        std::sort(planned.begin(), planned.end());
        for (std::size_t p = 0; p < add.size(); ++p)
          if (add[p] > 0) want.push_back(std::uint32_t(p));
        ASSERT_EQ(planned, want) << "min " << min << " threshold " << threshold << " pass " << passes;
        if (a == 0) break;
        ++passes;
      }
      if (threshold < 0.5) {
        EXPECT_GE(passes, 3) << "min " << min << " threshold " << threshold;
      }
    }
  // A change two pixels away: pixel (10, 10) stands out, so the 5×5 block around it refines; the
  // block's edge pixel (12, 10) then sees the bright value too, which makes (13, 10) (one sample)
  // contrast with it, so (14, 10), two pixels from any change, must refine now.
  SyntheticFilm f(24, 20);
  f.value = [](int x, int row, std::uint32_t s) {
    return row == 10 && (x == 10 || (x == 12 && s >= 1)) ? 0.8 : 0.1;
  };
  std::vector<std::uint32_t> add(f.counts.size(), 1), full(f.counts.size(), 0);
  AdaptivePlanner incremental, every_pixel;
  for (int pass = 0; pass < 2; ++pass) {
    f.take(add);
    EXPECT_EQ(f.counts[10 * 24 + 13], 1u);  // no change nearer than (12, 10)
    incremental.plan(f.film, f.counts, 64, 0.5, add);
    every_pixel.plan(f.film, f.counts, 64, 0.5, full, true);
    ASSERT_EQ(add, full) << "pass " << pass;
  }
  EXPECT_GT(add[10 * 24 + 14], 0u);
}

// The plan from scratch (the first pass's) is the rule of adaptive.h applied to pixel_error() pixel
// by pixel: each pixel doubles its count when it or a neighbour is over the threshold.
TEST(AdaptivePlanner, PlanOfEveryPixelFollowsPixelError) {
  for (const std::uint32_t min : {1u, 2u})
    for (const double threshold : {0.05, 0.2, 0.5}) {
      SyntheticFilm f(53, 37);
      f.second_disc = true;
      std::vector<std::uint32_t> add(f.counts.size(), min), full(f.counts.size(), 0);
      AdaptivePlanner planner;
      for (int pass = 0; pass < 4; ++pass) {
        f.take(add);
        const std::uint64_t total = planner.plan(f.film, f.counts, 16, threshold, full, true);
        std::uint64_t want_total = 0;
        std::size_t differ = 0;
        for (int row = 0; row < f.h; ++row)
          for (int x = 0; x < f.w; ++x) {
            bool refine = false;
            for (int ny = std::max(0, row - 1); ny <= std::min(f.h - 1, row + 1); ++ny)
              for (int nx = std::max(0, x - 1); nx <= std::min(f.w - 1, x + 1); ++nx)
                refine = refine || pixel_error(f.film, nx, ny) > threshold;
            const std::size_t p = std::size_t(row) * std::size_t(f.w) + std::size_t(x);
            const std::uint32_t c = f.counts[p];
            const std::uint32_t want = refine && c < 16 ? std::min(std::max(c, 1u), 16 - c) : 0;
            want_total += want;
            differ += full[p] != want;
          }
        EXPECT_EQ(differ, 0u) << "min " << min << " threshold " << threshold << " pass " << pass;
        EXPECT_EQ(total, want_total) << "min " << min << " threshold " << threshold << " pass " << pass;
        std::vector<std::uint32_t> planned = planner.planned(), want_planned;
        std::sort(planned.begin(), planned.end());
        for (std::size_t p = 0; p < full.size(); ++p)
          if (full[p] > 0) want_planned.push_back(std::uint32_t(p));
        EXPECT_EQ(planned, want_planned) << "the pixels planned() lists";
        add = full;
      }
    }
}

// Passes of 1, 1, 2, 4, … samples add up to the same image as one pass of all of them.
TEST(Progressive, PassesGiveTheSameImageAsOnePass) {
  for (const SamplingSettings& s :
       {sampling(SamplerKind::Sobol, 8), sampling(SamplerKind::Stratified, 9, FilterKind::Gaussian, 2)}) {
    const RenderScene rs = whitted(s);
    RenderStats one_stats, stats;
    const Image one = render(rs, {}, &one_stats);
    RenderOptions o;
    o.threads = 2;
    o.tile_size = 8;
    int checkpoints = 0;
    o.checkpoint_interval = 1e-9;  // after every tile
    o.checkpoint = [&](const Image& partial) {
      EXPECT_EQ(partial.width(), 40);
      ++checkpoints;
    };
    const Image passes = render(rs, o, &stats);
    EXPECT_TRUE(passes == one) << sampler_name(s.sampler) << ": max difference " << test::max_abs_diff(passes, one);
    EXPECT_EQ(one_stats.passes, 1);
    EXPECT_EQ(stats.passes, s.spp == 8 ? 4 : 5);
    EXPECT_EQ(stats.samples, 40u * 24u * std::uint64_t(rs.sampling.spp));
    EXPECT_GE(checkpoints, 1);
  }
}

TEST(Progressive, TimeLimitStopsWithTheImageSoFar) {
  const RenderScene rs = whitted(sampling(SamplerKind::Sobol, 1 << 16));
  RenderOptions o;
  o.time_limit = 1e-9;
  RenderStats stats;
  const Image img = render(rs, o, &stats);
  EXPECT_TRUE(stats.time_limited);
  EXPECT_FALSE(stats.cancelled);
  EXPECT_LT(stats.samples, 40u * 24u * (1u << 16));
  EXPECT_EQ(img.width(), 40);
  // Cancelled through the shared flag: same mechanism, reported as cancelled.
  std::atomic<bool> cancel{true};
  RenderOptions c;
  c.cancel = &cancel;
  RenderStats cstats;
  render(rs, c, &cstats);
  EXPECT_TRUE(cstats.cancelled);
  EXPECT_EQ(cstats.samples, 0u);
}

// AOVs on a known scene: a plane at distance 3 facing the camera, a sphere in front of its centre.
TEST(Aov, DepthNormalAlbedoAndIdOfAKnownScene) {
  Scene s;
  s.add(Plane({0, 0, 1}, -3, material_with_color({0.2, 0.4, 0.6})));  // object 0: z = −3
  s.add(Sphere({0, 0, -1.5}, 0.2, material_with_color({0.9, 0.1, 0.1})));  // object 1
  test::set_camera(s, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, -1, 1, -1, 1, 1, 9, 9);
  const RenderScene rs = compile(s);
  const AovImages a = render_aovs(rs, 2);
  // The centre pixel looks straight down −z at the sphere's front, 1.5 − 0.2 away.
  EXPECT_NEAR(a.depth.at(4, 4).r, 1.3, 1e-6);
  EXPECT_VEC_NEAR(test::to_vec(a.normal.at(4, 4)), Vec3(0, 0, 1), 1e-6);
  EXPECT_VEC_NEAR(test::to_vec(a.albedo.at(4, 4)), Vec3(0.9, 0.1, 0.1), 1e-6);
  EXPECT_EQ(a.id.at(4, 4).r, 1);
  // A corner pixel sees the plane at 3 / cos θ.
  const Ray ray = rs.camera.generate_ray(0.5, 0.5);  // bottom-left pixel = row 8
  EXPECT_NEAR(a.depth.at(0, 8).r, 3 / std::fabs(ray.direction.z), 1e-5);
  EXPECT_VEC_NEAR(test::to_vec(a.normal.at(0, 8)), Vec3(0, 0, 1), 1e-6);
  EXPECT_VEC_NEAR(test::to_vec(a.albedo.at(0, 8)), Vec3(0.2, 0.4, 0.6), 1e-6);
  EXPECT_EQ(a.id.at(0, 8).r, 0);
  // Looking away from everything: background values.
  Scene away;
  away.add(Plane({0, 0, 1}, -3, material_with_color({0.2, 0.4, 0.6})));
  test::set_camera(away, {0, 0, 0}, {0, 0, 1}, {0, 1, 0}, -1, 1, -1, 1, 1, 3, 3);
  const AovImages b = render_aovs(compile(away));
  EXPECT_TRUE(std::isinf(b.depth.at(1, 1).r));
  EXPECT_EQ(b.id.at(1, 1).r, -1);
  EXPECT_EQ(b.albedo.at(1, 1).g, 0);
}

}  // namespace
}  // namespace strahl::film_test
