// Every pixel is a pure function of the scene: the image is bit-identical for any thread count
// and tile size, and equals render_pixel() evaluated pixel by pixel.

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>

#include "strahl/scene/scene_file.h"
#include "test_helpers.h"

namespace strahl::determinism_test {
namespace {

RenderScene whitted_scene() {
  Scene s = load_scene(fs::path(STRAHL_SOURCE_DIR) / "scenes" / "lecture-whitted.yaml");
  s.settings.width = 64;
  s.settings.height = 36;
  s.settings.supersample = 2;
  return compile(s);
}

Image render_with(const RenderScene& rs, int threads, int tile, RenderStats* stats = nullptr) {
  RenderOptions o;
  o.threads = threads;
  o.tile_size = tile;
  return render(rs, o, stats);
}

TEST(Determinism, ThreadCountAndTileSizeDoNotChangeTheImage) {
  const RenderScene rs = whitted_scene();
  RenderStats reference_stats;
  const Image reference = render_with(rs, 1, 32, &reference_stats);
  ASSERT_EQ(reference.width(), 64);
  ASSERT_EQ(reference.height(), 36);
  // The scene exercises every kind of ray.
  EXPECT_EQ(reference_stats.rays.camera, 64u * 36u * 4u);
  EXPECT_GT(reference_stats.rays.shadow, 0u);
  EXPECT_GT(reference_stats.rays.reflection, 0u);
  EXPECT_GT(reference_stats.rays.refraction, 0u);
  struct Config { int threads, tile; };
  for (const Config& c : {Config{2, 32}, Config{2, 7}, Config{1, 64}, Config{2, 64}, Config{2, 1}, Config{1, 5},
                          Config{0, 32}}) {
    RenderStats stats;
    const Image img = render_with(rs, c.threads, c.tile, &stats);
    EXPECT_TRUE(img == reference) << c.threads << " threads, tile " << c.tile << ": max difference "
                                  << test::max_abs_diff(img, reference);
    EXPECT_EQ(stats.rays.total(), reference_stats.rays.total()) << c.threads << " threads, tile " << c.tile;
    EXPECT_EQ(stats.rays.reflection, reference_stats.rays.reflection);
    EXPECT_EQ(stats.rays.refraction, reference_stats.rays.refraction);
    EXPECT_EQ(stats.rays.shadow, reference_stats.rays.shadow);
  }
}

TEST(Determinism, RepeatedRendersAreIdentical) {
  const RenderScene rs = whitted_scene();
  const Image a = render_with(rs, 2, 16);
  const Image b = render_with(rs, 2, 16);
  EXPECT_TRUE(a == b);
}

TEST(Determinism, ImageEqualsRenderPixelPixelByPixel) {
  const RenderScene rs = whitted_scene();
  const Image img = render_with(rs, 2, 7);
  const SceneView view = rs.view();
  RayCounters counters;
  int lit = 0;
  for (int row = 0; row < img.height(); ++row)
    for (int x = 0; x < img.width(); ++x) {
      const Vec3 c = render_pixel(view, x, row, rs.supersample, counters);
      const Rgb expected{float(c.x), float(c.y), float(c.z)};
      ASSERT_TRUE(img.at(x, row) == expected) << "pixel " << x << "," << row;
      lit += c.x + c.y + c.z > 0.05;
    }
  EXPECT_GT(lit, img.width() * img.height() / 2) << "most of the lecture scene is visible";
}

TEST(Determinism, ProgressReachesTheTotalOnce) {
  const RenderScene rs = whitted_scene();
  std::atomic<long> calls{0}, max_done{0};
  long total_seen = 0;
  std::mutex m;
  RenderOptions o;
  o.threads = 2;
  o.tile_size = 16;
  render(rs, o, nullptr, [&](long done, long total) {
    ++calls;
    std::lock_guard lock(m);
    total_seen = total;
    if (done > max_done) max_done = done;
  });
  // Progress counts samples: 2×2 per pixel.
  EXPECT_EQ(total_seen, 64 * 36 * 4);
  EXPECT_EQ(max_done.load(), 64 * 36 * 4);
  EXPECT_EQ(calls.load(), 4 * 3) << "one call per tile";
}

}  // namespace
}  // namespace strahl::determinism_test
