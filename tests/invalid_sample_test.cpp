// No NaN or infinity reaches the image: a scene whose radiance overflows (two lights of 1e308,
// each finite and so accepted, whose sum is infinite; inf − inf and 0 · inf give NaN further on)
// renders to finite pixels only, with the bad samples black and counted in the statistics and
// reported by the CLI's summary.

#include <gtest/gtest.h>

#include <cmath>

#include "child_process.h"
#include "strahl/image/image_io.h"
#include "test_helpers.h"

namespace strahl::invalid_sample_test {
namespace {

Scene overflowing_scene() {
  Scene s;
  test::set_camera(s, Vec3(0, 0, 4), Vec3(0, 0, 0), Vec3(0, 1, 0), -1, 1, -1, 1, 2, 16, 16);
  s.settings.background = Vec3(0.25);
  Material m = test::phong(Vec3(1), 0, 1, Vec3(1), 10);
  m.reflectivity = 0.5;
  s.add(Sphere(Vec3(0, 0, 0), 1, m));
  s.add(point_light(Vec3(2, 2, 4), Vec3(1), 1e308));
  s.add(point_light(Vec3(-2, 2, 4), Vec3(1), 1e308));
  return s;
}

TEST(InvalidSamples, OverflowingRadianceBecomesBlackAndIsCounted) {
  RenderStats stats;
  const Image img = test::render_image(overflowing_scene(), 2, 8, &stats);
  long black = 0, background = 0;
  for (const Rgb& p : img.pixels()) {
    ASSERT_TRUE(std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b));
    black += (p.r == 0 && p.g == 0 && p.b == 0) ? 1 : 0;
    background += (p.r == 0.25f && p.g == 0.25f && p.b == 0.25f) ? 1 : 0;
  }
  EXPECT_GT(stats.rays.invalid_samples, 0u);
  EXPECT_EQ(std::uint64_t(black), stats.rays.invalid_samples) << "one sample per pixel: each bad one is a black pixel";
  EXPECT_GT(background, 0) << "rays that miss the sphere are untouched";
}

TEST(InvalidSamples, TheCliReportsThemAndWritesAFiniteImage) {
  test::TempDir dir;
  test::write_text(dir / "overflow.yaml", R"(camera: {position: [0, 0, 4], look_at: [0, 0, 0], fov: 40}
render: {width: 16, height: 16}
lights:
  - {type: point, position: [2, 2, 4], intensity: 1e308}
  - {type: point, position: [-2, 2, 4], intensity: 1e308}
objects:
  - {type: sphere, center: [0, 0, 0], radius: 1, material: {diffuse: 1, specular: 1}}
)");
  const test::ChildResult r = test::run_child({STRAHL_CLI, "overflow.yaml", "-o", "out.pfm"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("samples were NaN or infinite and were set to black"), std::string::npos) << r.out;
  const Image img = read_image(dir / "out.pfm");
  for (const Rgb& p : img.pixels()) ASSERT_TRUE(std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b));
}

}  // namespace
}  // namespace strahl::invalid_sample_test
