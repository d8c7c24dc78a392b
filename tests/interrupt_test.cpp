// Ctrl-C (SIGINT) and SIGTERM during a render: the CLI stops starting tiles, writes the image
// rendered so far (through the usual temporary file and rename) and exits with 130. The test
// waits for the first progress line, so the signal arrives while tiles are being rendered; it
// makes no assertion about timing (a render that finishes first still has to exit 130).

#include <gtest/gtest.h>

#include <chrono>

#include "child_process.h"
#include "strahl/image/image_io.h"
#include "test_helpers.h"

namespace strahl::interrupt_test {
namespace {

void interrupt_render(int sig, const char* name) {
  test::TempDir dir;
  const fs::path out = dir / "partial.pfm";
  // The built-in lecture scene, large and on one thread: many seconds if left alone.
  test::ChildProcess child({STRAHL_CLI, "--width", "1600", "--height", "1200", "--supersample", "4", "--threads", "1",
                            "--tile-size", "16", "-o", out.string()},
                           dir.path());
  ASSERT_TRUE(child.wait_for_stderr("rendering:", 120)) << "no progress line from the CLI";
  child.send(sig);
  const test::ChildResult r = child.wait(120);
  ASSERT_FALSE(r.timed_out);
  EXPECT_EQ(r.term_signal, 0) << "ended by the signal instead of handling it";
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_NE(r.err.find(std::string("interrupted (") + name + "); wrote the image rendered so far to"), std::string::npos)
      << r.err;
  ASSERT_TRUE(fs::is_regular_file(out));
  const Image img = read_image(out);
  EXPECT_EQ(img.width(), 1600);
  EXPECT_EQ(img.height(), 1200);
  // The tiles done before the progress line (a tenth of the image) are in it.
  long lit = 0;
  for (const Rgb& p : img.pixels()) lit += (p.r > 0 || p.g > 0 || p.b > 0) ? 1 : 0;
  EXPECT_GT(lit, 0);
  // Nothing but the image is left in the directory (no temporary file).
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

TEST(Interrupt, SigintWritesThePartialImageAndExits130) { interrupt_render(SIGINT, "SIGINT"); }
TEST(Interrupt, SigtermWritesThePartialImageAndExits130) { interrupt_render(SIGTERM, "SIGTERM"); }

// Issue 12: glass that reflects and refracts everywhere, the camera inside a glass shell,
// max_depth 64, min_weight 0: every camera ray's tree would double at each bounce. The ray
// budget (render.ray_budget) bounds each camera sample, and the stop flag is checked before every
// sample, so the time limit and SIGTERM act within a bounded time.
std::string exponential_scene(int width, int height) {
  return "camera: {position: [0, 0, 0], look_at: [0, 0, -1], fov: 60}\n"
         "render: {width: " + std::to_string(width) + ", height: " + std::to_string(height) +
         ", max_depth: 64, min_weight: 0}\n"
         "materials:\n"
         "  glass: {color: 1, ambient: 0, diffuse: 0.2, reflectivity: 0.5, transparency: 0.5, ior: 1.5}\n"
         "lights:\n"
         "  - {type: point, position: [0, 5, 0]}\n"
         "objects:\n"
         "  - {type: sphere, center: [0, 0, -3], radius: 1, material: glass}\n"
         "  - {type: sphere, center: [0, 0, 0], radius: 10, material: glass}\n";
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The number after `key` in the summary (e.g. "render " in "time  load 0.001 s, ... render 0.512 s").
double summary_number(const std::string& summary, const std::string& key) {
  const std::size_t at = summary.find(key);
  if (at == std::string::npos) return -1;
  return std::stod(summary.substr(at + key.size()));
}

TEST(Interrupt, ExponentialRayTreeFinishesAndTheSummaryCountsCutRays) {
  test::TempDir dir;
  test::write_text(dir / "glass.yaml", exponential_scene(8, 8));
  const test::ChildResult r =
      test::run_child({STRAHL_CLI, "glass.yaml", "--threads", "1", "-o", (dir / "glass.pfm").string()}, dir.path(), 60);
  ASSERT_FALSE(r.timed_out) << "an exponential ray tree was not bounded";
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("rays were cut: the ray budget of 4096 per camera sample (render.ray_budget) was spent"),
            std::string::npos)
      << r.out;
  // "rays  N total: 64 camera, S shadow, R reflection, F refraction": R + F is at most 64 budgets
  // (camera rays that miss the inner ball spawn fewer: their escaping rays end the branches).
  EXPECT_NE(r.out.find(" total: 64 camera, "), std::string::npos) << r.out;
  const double secondary = summary_number(r.out, " shadow, ") + summary_number(r.out, " reflection, ");
  EXPECT_LE(secondary, 64.0 * 4096) << r.out;
  EXPECT_GT(secondary, 16.0 * 4096) << r.out;
  EXPECT_LT(r.cpu_seconds, 20.0);
}

TEST(Interrupt, TimeLimitStopsAnExponentialSceneInTime) {
  test::TempDir dir;
  test::write_text(dir / "glass.yaml", exponential_scene(64, 48));
  const double limit = 0.5;
  const test::ChildResult r = test::run_child({STRAHL_CLI, "glass.yaml", "--threads", "2", "--spp", "16", "--time-limit",
                                               "0.5", "-o", (dir / "glass.pfm").string()},
                                              dir.path(), 60);
  ASSERT_FALSE(r.timed_out) << "--time-limit was ignored";
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("stopped by the time limit"), std::string::npos) << r.out;
  const double render = summary_number(r.out, "render ");
  EXPECT_GE(render, limit) << r.out;
  EXPECT_LE(render, limit + 0.2) << "the time limit took effect " << render - limit << " s late\n" << r.out;
}

TEST(Interrupt, SigtermStopsAnExponentialSceneInTime) {
  test::TempDir dir;
  test::write_text(dir / "glass.yaml", exponential_scene(64, 48));
  const fs::path out = dir / "glass.pfm";
  // One thread, 8-pixel tiles: the 10% progress line comes after a few tiles, the whole image would take minutes.
  test::ChildProcess child({STRAHL_CLI, "glass.yaml", "--threads", "1", "--tile-size", "8", "-o", out.string()},
                           dir.path());
  ASSERT_TRUE(child.wait_for_stderr("rendering:", 120)) << "no progress line from the CLI";
  const auto sent = std::chrono::steady_clock::now();
  child.send(SIGTERM);
  const test::ChildResult r = child.wait(120);
  const double latency = seconds_since(sent);
  ASSERT_FALSE(r.timed_out) << "SIGTERM was ignored";
  EXPECT_EQ(r.term_signal, 0);
  EXPECT_EQ(r.exit_code, 130) << r.err;
  // Within 0.2 s of rendering, plus writing a 64x48 image and ending the process.
  EXPECT_LT(latency, 0.4) << "SIGTERM took effect after " << latency << " s";
  const Image img = read_image(out);
  EXPECT_EQ(img.width(), 64);
}

}  // namespace
}  // namespace strahl::interrupt_test
