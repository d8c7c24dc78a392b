// Image files: float formats round-trip exactly, 8-bit formats within one step of 1/255, the
// sRGB encoding, unknown extensions, and no temporary files left behind.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <set>

#include "strahl/image/image_io.h"
#include "strahl/image/metrics.h"
#include "test_helpers.h"

namespace strahl::image_io_test {
namespace {

// A non-square image whose every value differs, including HDR values above 1 and tiny ones.
Image hdr_test_image() {
  Image img(5, 3);
  for (int row = 0; row < 3; ++row)
    for (int x = 0; x < 5; ++x) {
      const float k = float(row * 5 + x);
      img.at(x, row) = Rgb{0.123456789f * k, 3.5f + k * 1.1f, k * 1e-7f + 1e-30f};
    }
  img.at(4, 2) = Rgb{65504.0f, 1e-38f, 0.1f};
  return img;
}

// Values in [0, 1] for 8-bit formats.
Image ldr_test_image() {
  Image img(7, 4);
  for (int row = 0; row < 4; ++row)
    for (int x = 0; x < 7; ++x) {
      const float k = float(row * 7 + x) / 27.0f;
      img.at(x, row) = Rgb{k, 1.0f - k, std::fmod(k * 3.7f, 1.0f)};
    }
  return img;
}

std::set<std::string> files_in(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

class ImageIo : public ::testing::Test {
 protected:
  test::TempDir dir_;
};

TEST_F(ImageIo, PfmRoundTripsExactly) {
  const Image img = hdr_test_image();
  write_image(img, dir_ / "a.pfm");
  const Image back = read_image(dir_ / "a.pfm");
  EXPECT_TRUE(back == img) << "max difference " << test::max_abs_diff(back, img);
  EXPECT_EQ(files_in(dir_.path()), std::set<std::string>{"a.pfm"});
}

TEST_F(ImageIo, ExrRoundTripsExactly) {
  const Image img = hdr_test_image();
  write_image(img, dir_ / "a.exr");
  const Image back = read_image(dir_ / "a.exr");
  EXPECT_TRUE(back == img) << "max difference " << test::max_abs_diff(back, img);
  EXPECT_EQ(files_in(dir_.path()), std::set<std::string>{"a.exr"});
}

TEST_F(ImageIo, PfmRowOrderIsBottomUpOnDisk) {
  // The PFM format stores the bottom row first: the first float is the bottom-left red value.
  Image img(2, 2);
  img.at(0, 1) = Rgb{7, 8, 9};  // bottom-left
  write_image(img, dir_ / "o.pfm");
  const std::string bytes = test::read_text(dir_ / "o.pfm");
  const std::size_t header_end = bytes.find("-1.0\n");
  ASSERT_NE(header_end, std::string::npos) << "little-endian scale";
  float first = 0;
  std::memcpy(&first, bytes.data() + header_end + 5, sizeof first);
  EXPECT_EQ(first, 7.0f);
  EXPECT_EQ(bytes.rfind("PF\n2 2\n", 0), 0u);
}

TEST_F(ImageIo, ReadsGreyAndBigEndianPfm) {
  // "Pf" is one channel; a positive scale means big-endian floats. Rows run bottom-up.
  std::string bytes = "Pf\n1 2\n1.0\n";
  for (float v : {0.25f, 2.5f}) {  // bottom row, then top row
    unsigned char b[4];
    std::memcpy(b, &v, 4);
    bytes += std::string{char(b[3]), char(b[2]), char(b[1]), char(b[0])};
  }
  test::write_text(dir_ / "g.pfm", bytes);
  const Image img = read_image(dir_ / "g.pfm");
  ASSERT_EQ(img.width(), 1);
  ASSERT_EQ(img.height(), 2);
  EXPECT_TRUE(img.at(0, 0) == (Rgb{2.5f, 2.5f, 2.5f}));
  EXPECT_TRUE(img.at(0, 1) == (Rgb{0.25f, 0.25f, 0.25f}));
}

TEST_F(ImageIo, LinearPngAndPpmRoundTripWithinOneStep) {
  const Image img = ldr_test_image();
  for (const char* name : {"a.png", "a.ppm"}) {
    write_image(img, dir_ / name, {true});
    const Image back = read_image(dir_ / name);
    ASSERT_EQ(back.width(), img.width()) << name;
    ASSERT_EQ(back.height(), img.height()) << name;
    EXPECT_LE(test::max_abs_diff(back, img), 0.5f / 255 + 1e-6f) << name;
    // Exactly the rounded byte.
    for (int row = 0; row < img.height(); ++row)
      for (int x = 0; x < img.width(); ++x)
        EXPECT_NEAR(back.at(x, row).g, float(to_byte(img.at(x, row).g)) / 255.0f, 1e-7) << name;
  }
  EXPECT_EQ(files_in(dir_.path()), (std::set<std::string>{"a.png", "a.ppm"}));
}

TEST_F(ImageIo, SrgbPngStoresEncodedValues) {
  const Image img = ldr_test_image();
  write_image(img, dir_ / "s.png");  // default: sRGB
  const Image back = read_image(dir_ / "s.png");
  for (int row = 0; row < img.height(); ++row)
    for (int x = 0; x < img.width(); ++x) {
      const Rgb& p = img.at(x, row);
      const Vec3 expected(linear_to_srgb(p.r), linear_to_srgb(p.g), linear_to_srgb(p.b));
      EXPECT_VEC_NEAR(test::to_vec(back.at(x, row)), expected, 0.5 / 255 + 1e-6);
    }
}

TEST_F(ImageIo, JpegRoundTripsApproximately) {
  Image img(16, 16);
  for (int row = 0; row < 16; ++row)
    for (int x = 0; x < 16; ++x) img.at(x, row) = Rgb{0.5f, 0.25f, 0.75f};
  write_image(img, dir_ / "a.jpg", {true});
  const Image back = read_image(dir_ / "a.jpg");
  EXPECT_EQ(back.width(), 16);
  EXPECT_LE(test::max_abs_diff(back, img), 3.0f / 255);
}

TEST_F(ImageIo, EightBitClampsOutOfRangeAndNan) {
  Image img(3, 1);
  img.at(0, 0) = Rgb{-1, 2, std::numeric_limits<float>::quiet_NaN()};
  img.at(1, 0) = Rgb{0, 1, 1e9f};
  img.at(2, 0) = Rgb{std::numeric_limits<float>::infinity(), -0.0f, 0.5f};
  write_image(img, dir_ / "c.ppm", {true});
  const Image back = read_image(dir_ / "c.ppm");
  EXPECT_TRUE(back.at(0, 0) == (Rgb{0, 1, 0}));
  EXPECT_TRUE(back.at(1, 0) == (Rgb{0, 1, 1}));
  EXPECT_TRUE(back.at(2, 0) == (Rgb{1, 0, 128 / 255.0f}));
}

TEST(ImageEncoding, SrgbTransferFunction) {
  EXPECT_EQ(linear_to_srgb(0), 0);
  EXPECT_EQ(linear_to_srgb(1), 1);
  EXPECT_EQ(linear_to_srgb(-0.5f), 0);
  EXPECT_EQ(linear_to_srgb(7), 1);
  EXPECT_NEAR(linear_to_srgb(0.002f), 12.92f * 0.002f, 1e-7);               // linear segment
  EXPECT_NEAR(linear_to_srgb(0.5f), 1.055 * std::pow(0.5, 1 / 2.4) - 0.055, 1e-6);  // 0.7354
  EXPECT_NEAR(linear_to_srgb(0.0031308f), 0.04045, 1e-5);                  // continuous at the knee
  EXPECT_NEAR(linear_to_srgb(0.18f), 0.4614, 1e-4);
  EXPECT_EQ(to_byte(0), 0);
  EXPECT_EQ(to_byte(1), 255);
  EXPECT_EQ(to_byte(0.5f), 128);
  EXPECT_EQ(to_byte(100.0f / 255), 100);
}

// to_byte rounds v · 255 half away from zero, as std::lround does: tried on the 4097 floats
// around every half step (k + 0.5) / 255, where a float's own "+ 0.5f" or a truncation goes wrong,
// and on NaN, infinities and values outside 0 … 1.
TEST(ImageEncoding, ToByteRoundsLikeLround) {
  int wrong = 0;
  for (int k = 0; k < 255; ++k) {
    float v = (float(k) + 0.5f) / 255.0f;
    for (int i = 0; i < 2048; ++i) v = std::nextafter(v, 0.0f);
    for (int i = 0; i <= 4096; ++i, v = std::nextafter(v, 1.0f))
      wrong += to_byte(v) != static_cast<unsigned char>(std::lround(v * 255.0f));
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(to_byte(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(to_byte(-std::numeric_limits<float>::infinity()), 0);
  EXPECT_EQ(to_byte(std::numeric_limits<float>::infinity()), 255);
  EXPECT_EQ(to_byte(-0.0f), 0);
  EXPECT_EQ(to_byte(1.0001f), 255);
  EXPECT_EQ(to_byte(std::numeric_limits<float>::denorm_min()), 0);
}

TEST_F(ImageIo, UppercaseExtensionsWork) {
  const Image img = hdr_test_image();
  write_image(img, dir_ / "UP.PFM");
  EXPECT_TRUE(read_image(dir_ / "UP.PFM") == img);
  EXPECT_TRUE(is_supported_image_extension("x.EXR"));
  EXPECT_TRUE(is_supported_image_extension("x.Png"));
}

TEST_F(ImageIo, UnknownExtensionThrowsAndWritesNothing) {
  const Image img = ldr_test_image();
  EXPECT_THROW(write_image(img, dir_ / "a.xyz"), Error);
  EXPECT_THROW(write_image(img, dir_ / "noext"), Error);
  EXPECT_THROW(write_image(img, dir_ / "a.png.bak"), Error);
  EXPECT_FALSE(is_supported_image_extension("a.bmp"));
  EXPECT_FALSE(is_supported_image_extension("a"));
  EXPECT_TRUE(files_in(dir_.path()).empty());
}

TEST_F(ImageIo, MissingDirectoryThrowsAndWritesNothing) {
  EXPECT_THROW(write_image(ldr_test_image(), dir_ / "no" / "a.png"), Error);
  EXPECT_TRUE(files_in(dir_.path()).empty());
}

TEST_F(ImageIo, OverwritingReplacesTheFileAndLeavesNoTemporaries) {
  const Image a = hdr_test_image();
  Image b = hdr_test_image();
  b.at(0, 0) = Rgb{42, 43, 44};
  for (const char* name : {"x.pfm", "x.exr", "x.png", "x.ppm", "x.jpg"}) {
    write_image(a, dir_ / name);
    write_image(b, dir_ / name);
  }
  EXPECT_TRUE(read_image(dir_ / "x.pfm") == b);
  EXPECT_TRUE(read_image(dir_ / "x.exr") == b);
  EXPECT_EQ(files_in(dir_.path()), (std::set<std::string>{"x.pfm", "x.exr", "x.png", "x.ppm", "x.jpg"}));
}

TEST_F(ImageIo, ReadingMissingOrGarbageFilesThrows) {
  EXPECT_THROW(read_image(dir_ / "absent.png"), Error);
  test::write_text(dir_ / "junk.png", "this is not a png");
  EXPECT_THROW(read_image(dir_ / "junk.png"), Error);
  test::write_text(dir_ / "junk.pfm", "PF\n4 4\n-1.0\nshort");
  EXPECT_THROW(read_image(dir_ / "junk.pfm"), Error);
  test::write_text(dir_ / "junk.exr", "nope");
  EXPECT_THROW(read_image(dir_ / "junk.exr"), Error);
}

TEST(ImageMetrics, RmseAndPsnr) {
  Image a(2, 1), b(2, 1);
  b.at(0, 0) = Rgb{0.3f, 0.3f, 0.3f};  // 3 channels of 0.3 out of 6: mean square 0.045
  EXPECT_NEAR(rmse(a, b), std::sqrt(0.045), 1e-7);
  EXPECT_NEAR(psnr(a, b), 20 * std::log10(1 / std::sqrt(0.045)), 1e-5);
  EXPECT_EQ(rmse(a, a), 0);
  EXPECT_THROW(rmse(a, Image(1, 2)), Error);
}

}  // namespace
}  // namespace strahl::image_io_test
