// The format limits of the writers (docs/cli.md, "Output formats"): each writer refuses, before
// any work, a size its format cannot hold or its reader cannot read back, and every size it
// accepts reads back as written. Checked at the limits that are cheap to write (one row or one
// column), and just over each limit.

#include <gtest/gtest.h>

#include <string>

#include "child_process.h"
#include "strahl/image/image_io.h"
#include "strahl/util/error.h"
#include "test_helpers.h"

namespace strahl::image_limits_test {
namespace {

std::string refusal(const fs::path& path, int w, int h) {
  try {
    check_image_size(path, w, h);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ImageLimits, EachFormatRefusesWhatItCannotHold) {
  EXPECT_EQ(refusal("a.jpg", 65535, 65535), "");
  EXPECT_EQ(refusal("a.jpg", 65536, 1), "a.jpg: a JPEG image holds at most 65535 pixels per side, not 65536x1");
  EXPECT_EQ(refusal("a.JPEG", 1, 65536), "a.JPEG: a JPEG image holds at most 65535 pixels per side, not 1x65536");
  for (const char* name : {"a.png", "a.ppm", "a.pfm"}) {
    SCOPED_TRACE(name);
    EXPECT_EQ(refusal(name, 1 << 24, 1), "");
    EXPECT_NE(refusal(name, (1 << 24) + 1, 1).find("at most 16777216 pixels per side"), std::string::npos);
    EXPECT_NE(refusal(name, 1, (1 << 24) + 1).find("at most 16777216 pixels per side"), std::string::npos);
  }
  EXPECT_EQ(refusal("a.exr", (1 << 24) + 1, 1), "");
  // PNG: (3w + 1)·h bytes of filtered rows in stb's ints, at most 2^30.
  EXPECT_EQ(refusal("a.png", 16384, 21844), "");  // 49153 · 21844 = 1073698132 bytes
  EXPECT_NE(refusal("a.png", 16384, 21846).find("2^30 bytes of rows"), std::string::npos);
  // PPM: 3·w·h below 2^31 for stb's reader.
  EXPECT_EQ(refusal("a.ppm", 32768, 21845), "");
  EXPECT_NE(refusal("a.ppm", 32768, 21846).find("2^31 - 1 bytes"), std::string::npos);
  for (const char* name : {"a.png", "a.jpg", "a.ppm", "a.pfm", "a.exr"})
    EXPECT_NE(refusal(name, 0, 5).find("at least one pixel"), std::string::npos) << name;
}

// strahl's own limit is 65536 pixels per side: every format but JPEG takes a full row or column.
TEST(ImageLimits, WrittenImagesReadBackWithTheirSize) {
  test::TempDir dir;
  struct Size {
    int w, h;
  };
  for (const char* name : {"a.png", "a.ppm", "a.pfm", "a.exr", "a.jpg"})
    for (Size s : {Size{65536, 1}, Size{1, 65536}, Size{65535, 1}, Size{1, 1}, Size{3, 7}, Size{7, 3}}) {
      const bool jpeg = std::string(name) == "a.jpg";
      SCOPED_TRACE(std::string(name) + " " + std::to_string(s.w) + "x" + std::to_string(s.h));
      Image img(s.w, s.h);
      img.at(s.w - 1, s.h - 1) = Rgb{1, 1, 1};
      const fs::path path = dir / name;
      fs::remove(path);
      if (jpeg && (s.w > 65535 || s.h > 65535)) {
        EXPECT_THROW(write_image(img, path), Error);
        EXPECT_FALSE(fs::exists(path));
        EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 0);
        continue;
      }
      write_image(img, path);
      const Image back = read_image(path);
      EXPECT_EQ(back.width(), s.w);
      EXPECT_EQ(back.height(), s.h);
      if (!jpeg) {
        EXPECT_EQ(back.at(s.w - 1, s.h - 1), (Rgb{1, 1, 1}));
      }
      fs::remove(path);
    }
}

// The same through the command line, for the main image and an AOV: what strahl writes at the
// largest sizes each format holds (one row or column, cheap to render) reads back at that size.
TEST(ImageLimits, EveryImageTheCliWritesReadsBackWithItsSize) {
  test::TempDir dir;
  struct Case {
    const char* name;
    int w, h;
  };
  for (const Case& c : {Case{"a.png", 65536, 1}, Case{"a.ppm", 1, 65536}, Case{"a.pfm", 65536, 1},
                        Case{"a.exr", 1, 65536}, Case{"a.jpg", 65535, 1}, Case{"a.jpeg", 1, 65535}}) {
    SCOPED_TRACE(c.name);
    const test::ChildResult r = test::run_child({STRAHL_CLI, "--width", std::to_string(c.w), "--height",
                                                 std::to_string(c.h), "-q", "--aov", "depth", "-o", c.name},
                                                dir.path(), 120);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const fs::path& written : {dir / c.name, (dir / c.name).replace_extension(".depth.exr")}) {
      const Image back = read_image(written);
      EXPECT_EQ(back.width(), c.w) << written;
      EXPECT_EQ(back.height(), c.h) << written;
      fs::remove(written);
    }
  }
}

// A PFM header promising more than the file holds is refused before its memory is taken.
TEST(ImageLimits, LyingPfmHeaderIsRefusedWithoutTheMemory) {
  test::TempDir dir;
  test::write_text(dir / "lie.pfm", "PF\n16777216 16777216\n-1.0\n0123456789ab");
  try {
    read_image(dir / "lie.pfm");
    ADD_FAILURE() << "read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("truncated PFM file"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace strahl::image_limits_test
