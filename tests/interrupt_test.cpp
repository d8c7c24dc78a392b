// Ctrl-C (SIGINT) and SIGTERM during a render: the CLI stops starting tiles, writes the image
// rendered so far (through the usual temporary file and rename) and exits with 130. The test
// waits for the first progress line, so the signal arrives while tiles are being rendered; it
// makes no assertion about timing (a render that finishes first still has to exit 130).

#include <gtest/gtest.h>

#include "child_process.h"
#include "strahl/image/image_io.h"
#include "test_helpers.h"

namespace strahl {
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

}  // namespace
}  // namespace strahl
