// Closed, full and broken stdout/stderr (2>&-, 2>/dev/full, >/dev/full, | head): a message that
// cannot be written never ends a program. `strahl` still writes its image and exits 0 (its
// product is the image); `strahl-diff`, whose product is its report, exits 2 when the report is
// lost. docs/cli.md, "Streams and signals".

#include <gtest/gtest.h>

#include "child_process.h"
#include "console.h"
#include "strahl/image/image_io.h"
#include "test_helpers.h"

namespace strahl::streams_test {
namespace {

using test::Stream;

const char* kScene = R"(camera: {position: [0, 1, 3], look_at: [0, 0, 0], fov: 40}
render: {width: 48, height: 32}
lights:
  - {type: point, position: [2, 3, 2]}
objects:
  - {type: sphere, center: [0, 0, 0], radius: 1, material: {color: [0.9, 0.2, 0.1]}}
)";

const char* name(Stream s) {
  switch (s) {
    case Stream::captured: return "captured";
    case Stream::closed: return "closed";
    case Stream::full: return "/dev/full";
    case Stream::broken_pipe: return "a broken pipe";
  }
  return "?";
}

class Streams : public ::testing::Test {
 protected:
  void SetUp() override { test::write_text(dir_ / "scene.yaml", kScene); }

  // Renders with progress, checkpoints, an AOV and the summary, so that both streams are written
  // before, during and after the image; the image must be complete whatever the streams are.
  void expect_image_written(test::Streams streams) {
    SCOPED_TRACE(std::string("stdout ") + name(streams.out) + ", stderr " + name(streams.err));
    const fs::path out = dir_ / "out.ppm";
    fs::remove(out);
    const test::ChildResult r =
        test::run_child({STRAHL_CLI, "scene.yaml", "--checkpoint", "0.001", "--aov", "depth", "-o", out.string()},
                        dir_.path(), 30, streams);
    ASSERT_FALSE(r.timed_out);
    EXPECT_EQ(r.term_signal, 0) << "ended by signal " << r.term_signal;
    EXPECT_EQ(r.exit_code, 0) << r.err;
    ASSERT_TRUE(fs::is_regular_file(out));
    const Image img = read_image(out);
    EXPECT_EQ(img.width(), 48);
    EXPECT_EQ(img.height(), 32);
    EXPECT_GT(img.at(24, 16).r, 0.1f);  // the red sphere, rendered
    EXPECT_EQ(read_image(dir_ / "out.depth.exr").width(), 48);
    for (const auto& e : fs::directory_iterator(dir_.path()))
      EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
  }

  test::TempDir dir_;
};

TEST_F(Streams, StrahlWritesItsImageWhateverStderrIs) {
  for (Stream err : {Stream::closed, Stream::full, Stream::broken_pipe}) expect_image_written({Stream::captured, err});
}

TEST_F(Streams, StrahlWritesItsImageWhateverStdoutIs) {
  for (Stream out : {Stream::closed, Stream::full, Stream::broken_pipe}) expect_image_written({out, Stream::captured});
  expect_image_written({Stream::closed, Stream::closed});
  expect_image_written({Stream::full, Stream::broken_pipe});
}

// An error with nowhere to report it still ends with its own exit code, not a crash.
TEST_F(Streams, ErrorsKeepTheirExitCodes) {
  test::write_text(dir_ / "bad.yaml", "objects:\n  - {type: sphere, center: [0, 0, 0], radius: -1}\n");
  for (Stream err : {Stream::closed, Stream::full, Stream::broken_pipe}) {
    SCOPED_TRACE(std::string("stderr ") + name(err));
    const test::Streams s{Stream::captured, err};
    EXPECT_EQ(test::run_child({STRAHL_CLI, "bad.yaml", "-o", "x.png"}, dir_.path(), 30, s).exit_code, 2);
    EXPECT_EQ(test::run_child({STRAHL_CLI, "--width", "0"}, dir_.path(), 30, s).exit_code, 1);
    const test::ChildResult help = test::run_child({STRAHL_CLI, "--help"}, dir_.path(), 30, {err, Stream::captured});
    EXPECT_EQ(help.term_signal, 0);
    EXPECT_EQ(help.exit_code, 0);
  }
}

// strahl-diff's report is its product: losing it is an error (2), a closed stdout is /dev/null.
TEST_F(Streams, DiffFailsWhenItsReportIsLost) {
  write_image(Image(4, 2), dir_ / "a.pfm");
  const auto diff = [&](test::Streams s) {
    return test::run_child({STRAHL_DIFF, "a.pfm", "a.pfm"}, dir_.path(), 30, s);
  };
  EXPECT_EQ(diff({Stream::captured, Stream::captured}).exit_code, 0);
  for (Stream out : {Stream::full, Stream::broken_pipe}) {
    SCOPED_TRACE(std::string("stdout ") + name(out));
    const test::ChildResult r = diff({out, Stream::captured});
    EXPECT_EQ(r.term_signal, 0);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("strahl-diff: error: the result could not be written to stdout"), std::string::npos) << r.err;
  }
  EXPECT_EQ(diff({Stream::closed, Stream::closed}).exit_code, 0);
  EXPECT_EQ(diff({Stream::captured, Stream::full}).exit_code, 0);
}

// A closed descriptor 0, 1 or 2 is reopened on /dev/null: otherwise the next file opened (the
// image) would get number 2 and receive the progress lines meant for stderr.
TEST(ProtectStreams, ReopensClosedStandardDescriptors) {
  test::TempDir dir;
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::close(STDOUT_FILENO);
    ::close(STDERR_FILENO);
    console::protect_streams();
    const int fd = ::open((dir / "image").c_str(), O_WRONLY | O_CREAT, 0600);
    console::err("a progress line\n");
    ::_exit(fd > STDERR_FILENO && ::fcntl(STDOUT_FILENO, F_GETFD) != -1 ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the image file got descriptor 1 or 2";
  EXPECT_EQ(fs::file_size(dir / "image"), 0u);
}

}  // namespace
}  // namespace strahl::streams_test
