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

using test::error_of;

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


// An output path that is a symbolic link is followed, through chains and relative links, to the
// file that is then written: the links stay. A link to a name not yet there creates it; a link
// to a device is refused like the device; a loop of links is an error, not a hang.
TEST(OutputFile, SymbolicLinksAreFollowedAndKept) {
  test::TempDir dir;
  fs::create_directory(dir / "sub");
  write_image(Image(1, 1), dir / "b.png");
  fs::create_symlink("b.png", dir / "link.png");
  fs::create_symlink("link.png", dir / "chain.png");
  fs::create_symlink("../b.png", dir / "sub" / "relative.png");
  int width = 2;
  for (const char* name : {"link.png", "chain.png", "sub/relative.png"}) {
    SCOPED_TRACE(name);
    EXPECT_NO_THROW(check_output_path(dir / name));
    write_image(Image(width, 1), dir / name);
    EXPECT_EQ(read_image(dir / "b.png").width(), width++);
    EXPECT_TRUE(fs::is_symlink(dir / name));
  }
  EXPECT_TRUE(fs::is_symlink(dir / "link.png"));
  fs::create_symlink("made.png", dir / "new.png");
  write_image(Image(7, 1), dir / "new.png");
  EXPECT_TRUE(fs::is_symlink(dir / "new.png"));
  EXPECT_EQ(read_image(dir / "made.png").width(), 7);
  EXPECT_EQ(entries(dir.path()), 6u);  // sub, b, link, chain, new, made: no temporary file left
  EXPECT_EQ(entries(dir / "sub"), 1u);

  fs::create_symlink("/dev/null", dir / "null.png");
  EXPECT_NE(error_of([&] { check_output_path(dir / "null.png"); })
                .find("(-> /dev/null): cannot write the image: it exists and is not a regular file"),
            std::string::npos);
  EXPECT_TRUE(fs::is_symlink(dir / "null.png"));
  fs::create_symlink("loop2.png", dir / "loop1.png");
  fs::create_symlink("loop1.png", dir / "loop2.png");
  EXPECT_NE(error_of([&] { check_output_path(dir / "loop1.png"); }).find("Too many levels of symbolic links"),
            std::string::npos);
  EXPECT_NE(error_of([&] { write_image(Image(1, 1), dir / "loop1.png"); }).find("Too many levels of symbolic links"),
            std::string::npos);
  EXPECT_TRUE(fs::is_symlink(dir / "loop1.png"));
  EXPECT_EQ(entries(dir.path()), 9u);
}

}  // namespace
}  // namespace strahl::output_file_test
