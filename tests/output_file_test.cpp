// Safe writing (image/output_file.h): a temporary file beside the target, created exclusively,
// renamed over the target only when complete; on failure the target is untouched, nothing is
// left beside it, and the error names the real reason from errno, never "Success".

#include <gtest/gtest.h>

#include <string>

#include "child_process.h"
#include "strahl/image/image_io.h"
#include "strahl/image/output_file.h"
#include "strahl/util/error.h"
#include "test_helpers.h"

namespace strahl::output_file_test {
namespace {

std::size_t entries(const fs::path& dir) {
  return std::size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(OutputFile, CommitRenamesAndAFailedCommitNamesTheReason) {
  test::TempDir dir;
  {
    OutputFile f(dir / "a.bin");
    f.write("hello", 5);
    EXPECT_EQ(f.tell(), 5u);
    EXPECT_FALSE(fs::exists(dir / "a.bin"));  // only the temporary file so far
    f.commit();
  }
  EXPECT_EQ(test::read_text(dir / "a.bin"), "hello");
  EXPECT_EQ(entries(dir.path()), 1u);

  // A directory appears where the file should go (the defect was "cannot write: Success").
  {
    OutputFile f(dir / "b.exr");
    fs::create_directories(dir / "b.exr" / "inside");
    f.write("x", 1);
    EXPECT_EQ(error_of([&] { f.commit(); }), (dir / "b.exr").string() + ": cannot write the image: Is a directory");
  }
  EXPECT_EQ(entries(dir.path()), 2u) << "the temporary file was left";
  // Dropped without commit: removed.
  { OutputFile f(dir / "c.bin"); }
  EXPECT_FALSE(fs::exists(dir / "c.bin"));
  EXPECT_EQ(entries(dir.path()), 2u);
  // No directory to create it in.
  EXPECT_EQ(error_of([&] { OutputFile f(dir / "no" / "d.bin"); }),
            (dir / "no" / "d.bin").string() + ": cannot write the image: No such file or directory");
}

TEST(OutputFile, NeverOverwritesAnotherFileWithItsTemporaryName) {
  test::TempDir dir;
  const fs::path target = dir / "a.png";
  std::uint32_t serial = 0;
  {
    const OutputFile probe(target);
    const std::string name = probe.temporary_path().string();
    serial = std::uint32_t(std::stoul(name.substr(name.size() - 8), nullptr, 16));
    EXPECT_EQ(probe.temporary_path(), OutputFile::temporary_name(target, serial));
  }
  // The next temporary names belong to someone else (a stale run with the same pid): their
  // files stay as they are, and the image takes the first free name.
  for (std::uint32_t k = 1; k <= 4; ++k) test::write_text(OutputFile::temporary_name(target, serial + k), "someone else's");
  write_image(Image(2, 2), target);
  for (std::uint32_t k = 1; k <= 4; ++k)
    EXPECT_EQ(test::read_text(OutputFile::temporary_name(target, serial + k)), "someone else's");
  EXPECT_EQ(read_image(target).width(), 2);
  EXPECT_EQ(entries(dir.path()), 5u);
}

// A write that fails halfway (the file-size limit, RLIMIT_FSIZE: EFBIG): exit 2 with the reason,
// the existing image untouched, no temporary file left, for every format.
TEST(OutputFile, AFailedWriteInTheCliNamesTheReasonAndKeepsTheOldImage) {
  test::TempDir dir;
  test::write_text(dir / "scene.yaml", "camera: {position: [0, 1, 3], look_at: [0, 0, 0]}\nrender: {width: 400, height: 300}\n"
                                       "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1}\n");
  for (const char* name : {"out.pfm", "out.ppm", "out.exr", "out.png", "out.jpg"}) {
    SCOPED_TRACE(name);
    test::write_text(dir / name, "the old image");
    // ulimit -f counts blocks of 512 bytes in dash (1024 in bash): 2 is at most 2 KiB.
    const test::ChildResult r = test::run_child(
        {"/bin/sh", "-c", std::string("ulimit -f 2 && exec '" STRAHL_CLI "' scene.yaml -q -o ") + name}, dir.path());
    EXPECT_EQ(r.term_signal, 0) << "SIGXFSZ ended the process";
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err, std::string("strahl: error: ") + name + ": cannot write the image: File too large\n");
    EXPECT_EQ(test::read_text(dir / name), "the old image");
  }
  EXPECT_EQ(entries(dir.path()), 6u) << "a temporary file was left";
}

}  // namespace
}  // namespace strahl::output_file_test
