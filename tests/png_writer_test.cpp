// strahl's PNG encoder (image/png_writer.h; built where zlib is found): lossless for every filter
// and band size (decoded by stb_image, byte for byte), a valid file for a strict reader (every
// chunk's CRC, the zlib stream's Adler-32, which stb_image does not check, inflated by zlib), and
// write_image's .png stores exactly the 8-bit encoding of each pixel. The encoder writes 8 bits
// per sample only (no 16-bit PNG: read_image reads those, nothing in strahl writes them).

#include <gtest/gtest.h>

#ifdef STRAHL_HAVE_ZLIB
#include <stb_image.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "strahl/image/image_io.h"
#include "strahl/image/png_writer.h"
#include "test_helpers.h"
#include "test_random.h"
#endif

namespace strahl::png_writer_test {
namespace {

#ifdef STRAHL_HAVE_ZLIB

using Bytes = std::vector<unsigned char>;

std::uint32_t get32(const unsigned char* p) {
  return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | std::uint32_t(p[3]);
}

Bytes encode(const Bytes& pixels, int width, int height, int channels, const PngEncoding& encoding) {
  Bytes file;
  const bool ok = encode_png(pixels.data(), width, height, channels,
                             [&](const void* data, std::size_t size) {
                               const auto* p = static_cast<const unsigned char*>(data);
                               file.insert(file.end(), p, p + size);
                             },
                             encoding);
  EXPECT_TRUE(ok);
  return file;
}

// What a strict reader checks: the signature, IHDR first and IEND last, every chunk's CRC, and
// the IDAT chunks' zlib stream inflated by zlib (header check and Adler-32) to exactly
// (width × channels + 1) × height bytes, each row's filter byte one of 0…4.
::testing::AssertionResult strictly_valid(const Bytes& file, int width, int height, int channels, int* idat_chunks = nullptr) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (file.size() < 8 || std::memcmp(file.data(), kSignature, 8) != 0) return ::testing::AssertionFailure() << "signature";
  std::vector<std::string> types;
  Bytes zlib_stream;
  std::size_t at = 8;
  while (at < file.size()) {
    if (file.size() - at < 12) return ::testing::AssertionFailure() << "truncated chunk at " << at;
    const std::uint32_t length = get32(&file[at]);
    if (file.size() - at - 12 < length) return ::testing::AssertionFailure() << "chunk overruns the file at " << at;
    const std::string type(reinterpret_cast<const char*>(&file[at + 4]), 4);
    const uLong crc = crc32(crc32(0, Z_NULL, 0), &file[at + 4], uInt(length + 4));
    if (crc != get32(&file[at + 8 + length])) return ::testing::AssertionFailure() << "CRC of chunk " << types.size() << " (" << type << ")";
    if (type == "IHDR") {
      const unsigned char* h = &file[at + 8];
      static constexpr int kColourType[5] = {-1, 0, 4, 2, 6};
      if (length != 13 || get32(h) != std::uint32_t(width) || get32(h + 4) != std::uint32_t(height) || h[8] != 8 ||
          h[9] != kColourType[channels] || h[10] != 0 || h[11] != 0 || h[12] != 0)
        return ::testing::AssertionFailure() << "IHDR";
    }
    if (type == "IDAT") zlib_stream.insert(zlib_stream.end(), &file[at + 8], &file[at + 8] + length);
    types.push_back(type);
    at += 12 + length;
  }
  if (idat_chunks) *idat_chunks = int(std::count(types.begin(), types.end(), "IDAT"));
  if (types.size() < 3 || types.front() != "IHDR" || types.back() != "IEND")
    return ::testing::AssertionFailure() << "chunk order";
  const std::size_t stride = std::size_t(width) * std::size_t(channels) + 1;
  Bytes raw(stride * std::size_t(height) + 1);  // one byte more: a longer stream would fill it
  uLongf raw_size = uLongf(raw.size());
  const int status = uncompress(raw.data(), &raw_size, zlib_stream.data(), uLong(zlib_stream.size()));
  if (status != Z_OK) return ::testing::AssertionFailure() << "zlib's uncompress: " << status;
  if (raw_size != stride * std::size_t(height)) return ::testing::AssertionFailure() << "inflated to " << raw_size << " bytes";
  for (int y = 0; y < height; ++y)
    if (raw[std::size_t(y) * stride] > 4) return ::testing::AssertionFailure() << "filter byte of row " << y;
  return ::testing::AssertionSuccess();
}

// The pixels stb_image decodes from `file`, as stored (no conversion of channels).
Bytes decode(const Bytes& file, int& width, int& height, int& channels) {
  std::unique_ptr<stbi_uc, void (*)(void*)> data(
      stbi_load_from_memory(file.data(), int(file.size()), &width, &height, &channels, 0), stbi_image_free);
  if (!data) return {};
  return Bytes(data.get(), data.get() + std::size_t(width) * std::size_t(height) * std::size_t(channels));
}

// Random noise (no filter helps), flat runs and smooth ramps (every filter does), mixed by rows.
Bytes test_pixels(int width, int height, int channels, std::uint64_t seed) {
  test::Random rng(seed);
  Bytes p(std::size_t(width) * std::size_t(height) * std::size_t(channels));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width * channels; ++x) {
      unsigned char& v = p[std::size_t(y) * std::size_t(width) * std::size_t(channels) + std::size_t(x)];
      switch ((y / 3) % 3) {
        case 0: v = static_cast<unsigned char>(rng.uniform() * 256); break;
        case 1: v = static_cast<unsigned char>(x % channels == 0 ? 200 : 17); break;
        default: v = static_cast<unsigned char>(x * 7 + y * 3 + (x % channels) * 50); break;
      }
    }
  return p;
}

struct Size {
  int width, height, channels;
};

TEST(PngWriter, EveryFilterAndBandSizeDecodesToTheSameBytes) {
  const Size sizes[] = {{1, 1, 3}, {1, 9, 3}, {13, 1, 3}, {37, 29, 3}, {64, 40, 1}, {31, 17, 2}, {23, 19, 4}};
  for (const Size& s : sizes)
    for (int filter = -1; filter <= 4; ++filter)
      for (const bool run_length : {true, false})
        for (const std::size_t band : {std::size_t(1), std::size_t(100), std::size_t(256 * 1024)}) {
          PngEncoding e;
          e.filter = filter;
          e.run_length = run_length;
          e.band_bytes = band;  // 1 and 100: a band per row or a few, many sync-flushed streams
          const Bytes pixels = test_pixels(s.width, s.height, s.channels, std::uint64_t(filter + 7) * 131 + band);
          const Bytes file = encode(pixels, s.width, s.height, s.channels, e);
          const std::string what = std::to_string(s.width) + "x" + std::to_string(s.height) + "x" +
                                   std::to_string(s.channels) + " filter " + std::to_string(filter) +
                                   (run_length ? " rle" : "") + " band " + std::to_string(band);
          EXPECT_TRUE(strictly_valid(file, s.width, s.height, s.channels)) << what;
          int w = 0, h = 0, c = 0;
          const Bytes back = decode(file, w, h, c);
          ASSERT_EQ(w, s.width) << what;
          ASSERT_EQ(h, s.height) << what;
          ASSERT_EQ(c, s.channels) << what;
          EXPECT_TRUE(back == pixels) << what;
        }
}

// A 1920-wide image of a few default bands (5761 bytes a row: 45 rows a band), with the bands'
// windows primed across their boundaries.
TEST(PngWriter, ManyDefaultBandsDecodeToTheSameBytes) {
  const int width = 1920, height = 200;
  const Bytes pixels = test_pixels(width, height, 3, 99);
  const Bytes file = encode(pixels, width, height, 3, PngEncoding{});
  int idat_chunks = 0;
  EXPECT_TRUE(strictly_valid(file, width, height, 3, &idat_chunks));
  EXPECT_EQ(idat_chunks, 5);  // a chunk per band: ceil(200 / 45)
  int w = 0, h = 0, c = 0;
  EXPECT_TRUE(decode(file, w, h, c) == pixels);
}

// Red: the floats around each half step (x + 0.5) / 255, y - 20 ulps away, where rounding goes
// wrong first; green: a ramp from below 0 to above 1; blue: a pattern, with NaN and infinities.
Image rounding_test_image() {
  Image img(256, 41);
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      float r = (float(x) + 0.5f) / 255.0f;
      for (int i = 20; i < y; ++i) r = std::nextafter(r, 2.0f);
      for (int i = y; i < 20; ++i) r = std::nextafter(r, -1.0f);
      img.at(x, y) = Rgb{r, float(x) / 255.0f * 1.5f - 0.2f, float((x * y) % 17) / 16.0f};
    }
  img.at(0, 0).b = std::numeric_limits<float>::quiet_NaN();
  img.at(1, 0).b = std::numeric_limits<float>::infinity();
  img.at(2, 0).b = -std::numeric_limits<float>::infinity();
  return img;
}

// write_image's .png holds exactly each pixel's 8-bit encoding (to_byte, linear or sRGB): the
// writer's vectorised conversion gives the same bytes as to_byte.
TEST(PngWriter, WriteImageStoresTheEightBitEncoding) {
  test::TempDir dir;
  const Image img = rounding_test_image();
  for (const bool linear : {true, false}) {
    write_image(img, dir / "a.png", {linear});
    int w = 0, h = 0, c = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load((dir / "a.png").c_str(), &w, &h, &c, 0), stbi_image_free);
    ASSERT_TRUE(data);
    ASSERT_EQ(w, img.width());
    ASSERT_EQ(h, img.height());
    ASSERT_EQ(c, 3);
    int wrong = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const Rgb& p = img.at(x, y);
        const float v[3] = {p.r, p.g, p.b};
        for (int k = 0; k < 3; ++k)
          wrong += data.get()[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3 + std::size_t(k)] !=
                   to_byte(linear ? v[k] : linear_to_srgb(v[k]));
      }
    EXPECT_EQ(wrong, 0) << (linear ? "linear" : "sRGB");
  }
}

#else

TEST(PngWriter, NotBuiltWithoutZlib) { GTEST_SKIP() << "built without zlib: PNGs are written by stb_image_write"; }

#endif

}  // namespace
}  // namespace strahl::png_writer_test
