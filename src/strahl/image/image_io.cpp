#include "strahl/image/image_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <atomic>
#include <cerrno>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <new>
#include <sstream>
#include <system_error>
#include <vector>

#include "strahl/image/output_file.h"
#ifdef STRAHL_HAVE_ZLIB
#include "strahl/image/png_writer.h"
#endif
#include "strahl/util/error.h"
#include "strahl/util/system_error.h"

namespace strahl {
namespace fs = std::filesystem;

namespace {

constexpr long long kMaxJpegSide = 65535;          // 16-bit fields in the frame header
constexpr long long kMaxImageSide = 1 << 24;       // stb_image's STBI_MAX_DIMENSIONS; the PFM reader's limit
constexpr long long kMaxPngBytes = 1ll << 30;      // stb's int arithmetic, with room for deflate's growth
constexpr long long kMaxPpmBytes = 2147483647;     // stb_image's PNM reader: w·h·3 in an int

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// to_byte: v · 255 rounded half away from zero (as std::lround), 0 for NaN and v <= 0, 255 for
// v >= 1. Without branches or a library call, so that to_bytes' loop is vectorised: x - trunc(x)
// is exact in float for x in [0, 255] (Sterbenz), so the comparison with a half decides as lround
// does. The same byte as lround for every one of the 2^32 floats (checked once, exhaustively).
inline unsigned char byte_of(float v) {
  const float x = (v > 0 ? (v < 1 ? v : 1.0f) : 0.0f) * 255.0f;
  const int whole = static_cast<int>(x);
  return static_cast<unsigned char>(whole + (x - float(whole) >= 0.5f));
}

// n pixels' 8-bit encoding. Restrict parameters: a byte store may alias anything, and the
// compiler vectorises the linear loop only where it knows that it does not; not inlined, since
// the copies inlined into TBB's task body lost that knowledge and stayed scalar (GCC 12).
[[gnu::noinline]] void encode_bytes(const Rgb* __restrict in, std::size_t n, bool linear, unsigned char* __restrict out) {
  if (linear) {
    for (std::size_t i = 0; i < n; ++i) {
      out[3 * i + 0] = byte_of(in[i].r);
      out[3 * i + 1] = byte_of(in[i].g);
      out[3 * i + 2] = byte_of(in[i].b);
    }
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      out[3 * i + 0] = byte_of(linear_to_srgb(in[i].r));
      out[3 * i + 1] = byte_of(linear_to_srgb(in[i].g));
      out[3 * i + 2] = byte_of(linear_to_srgb(in[i].b));
    }
  }
}

// 8-bit encoding, in parallel: the sRGB curve costs a pow per channel (~0.1 s at 1080p).
// (Fresh pages, first written by the threads that encode them: util/zeroed_array.h.)
ZeroedArray<unsigned char> to_bytes(const Image& image, bool linear) {
  const auto& pixels = image.pixels();
  ZeroedArray<unsigned char> bytes(pixels.size() * 3);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pixels.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    encode_bytes(pixels.data() + r.begin(), r.size(), linear, bytes.data() + 3 * r.begin());
  });
  return bytes;
}

void write_ppm(const Image& image, OutputFile& out, bool linear) {
  const std::string header = "P6\n" + std::to_string(image.width()) + " " + std::to_string(image.height()) + "\n255\n";
  out.write(header.data(), header.size());
  const ZeroedArray<unsigned char> bytes = to_bytes(image, linear);
  out.write(bytes.data(), bytes.size());
}

// Portable float map: little-endian (negative scale), rows from the bottom up.
void write_pfm(const Image& image, OutputFile& out) {
  static_assert(std::endian::native == std::endian::little, "PFM rows are written as the machine stores floats");
  const std::string header = "PF\n" + std::to_string(image.width()) + " " + std::to_string(image.height()) + "\n-1.0\n";
  out.write(header.data(), header.size());
  static_assert(sizeof(Rgb) == 3 * sizeof(float), "an image row is its pixels' floats, r g b, back to back");
  if (image.width() == 0) return;
  for (int row = image.height() - 1; row >= 0; --row) out.write(&image.at(0, row), std::size_t(image.width()) * sizeof(Rgb));
}

// OpenEXR writes through this stream, so that its bytes go through OutputFile's checks too.
class ExrStream : public Imf::OStream {
 public:
  explicit ExrStream(OutputFile& out, const std::string& name) : Imf::OStream(name.c_str()), out_(out) {}
  void write(const char c[], int n) override { out_.write(c, std::size_t(n)); }
  std::uint64_t tellp() override { return out_.tell(); }
  void seekp(std::uint64_t pos) override { out_.seek(pos); }

 private:
  OutputFile& out_;
};

void write_exr(const Image& image, OutputFile& out, const fs::path& path) {
  try {
    Imf::Header header(image.width(), image.height());
    for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    ExrStream stream(out, path.string());
    Imf::OutputFile file(stream, header);
    Imf::FrameBuffer fb;
    char* base = const_cast<char*>(reinterpret_cast<const char*>(image.pixels().data()));
    const std::size_t xs = sizeof(Rgb), ys = sizeof(Rgb) * std::size_t(image.width());
    fb.insert("R", Imf::Slice(Imf::FLOAT, base + offsetof(Rgb, r), xs, ys));
    fb.insert("G", Imf::Slice(Imf::FLOAT, base + offsetof(Rgb, g), xs, ys));
    fb.insert("B", Imf::Slice(Imf::FLOAT, base + offsetof(Rgb, b), xs, ys));
    file.setFrameBuffer(fb);
    file.writePixels(image.height());
  } catch (const std::exception& e) {
    throw Error(path.string() + ": cannot write EXR: " + e.what());
  }
}

// stb calls this with each piece of the encoded file.
void to_output_file(void* context, void* data, int size) {
  static_cast<OutputFile*>(context)->write(data, std::size_t(size));
}

void write_by_extension(const Image& image, OutputFile& out, const fs::path& path, const std::string& ext, bool linear) {
  if (ext == ".pfm") return write_pfm(image, out);
  if (ext == ".exr") return write_exr(image, out, path);
  if (ext == ".ppm") return write_ppm(image, out, linear);
  const ZeroedArray<unsigned char> bytes = to_bytes(image, linear);
  int ok = 0;
#ifdef STRAHL_HAVE_ZLIB
  // strahl's own encoder (image/png_writer.h): 1080p in ~0.03 s rather than stb's ~0.14 s, files
  // 17–19 % smaller (docs/benchmark.md, "Writing the PNG").
  if (ext == ".png") {
    try {
      ok = encode_png(bytes.data(), image.width(), image.height(), 3,
                      [&](const void* data, std::size_t size) { out.write(data, size); });
    } catch (const std::bad_alloc&) {
      ok = 0;
    }
  }
#else
  stbi_write_png_compression_level = 4;  // stb's default (8) costs twice the time for ~5% smaller files
  if (ext == ".png")
    ok = stbi_write_png_to_func(to_output_file, &out, image.width(), image.height(), 3, bytes.data(), image.width() * 3);
#endif
  if (ext == ".jpg" || ext == ".jpeg")
    ok = stbi_write_jpg_to_func(to_output_file, &out, image.width(), image.height(), 3, bytes.data(), 95);
  if (!ok) throw Error(path.string() + ": cannot write the image: the encoder failed (out of memory?)");
}

Image read_pfm(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int w = 0, h = 0;
  double scale = 0;
  in >> magic >> w >> h >> scale;
  in.get();
  if (!in || (magic != "PF" && magic != "Pf") || w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide)
    throw Error(path.string() + ": not a valid PFM file");
  const int channels = magic == "PF" ? 3 : 1;
  // The header's size against the file's, before the memory is taken.
  const auto data_start = in.tellg();
  in.seekg(0, std::ios::end);
  const auto data_bytes = std::uint64_t(in.tellg() - data_start);
  in.seekg(data_start);
  if (data_bytes < std::uint64_t(w) * std::uint64_t(h) * std::uint64_t(channels) * sizeof(float))
    throw Error(path.string() + ": truncated PFM file");
  std::vector<float> data(std::size_t(w) * h * channels);
  in.read(reinterpret_cast<char*>(data.data()), std::streamsize(data.size() * sizeof(float)));
  if (!in) throw Error(path.string() + ": truncated PFM file");
  if (scale > 0)  // big-endian data
    for (float& f : data) { unsigned char* b = reinterpret_cast<unsigned char*>(&f); std::reverse(b, b + 4); }
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float* v = &data[(std::size_t(y) * w + x) * channels];
      image.at(x, h - 1 - y) = channels == 3 ? Rgb{v[0], v[1], v[2]} : Rgb{v[0], v[0], v[0]};
    }
  return image;
}

Image read_exr(const fs::path& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dw = file.header().dataWindow();
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    Image image(w, h);
    char* base = reinterpret_cast<char*>(&image.at(0, 0)) -
                 (std::ptrdiff_t(dw.min.x) + std::ptrdiff_t(dw.min.y) * w) * std::ptrdiff_t(sizeof(Rgb));
    const std::size_t xs = sizeof(Rgb), ys = sizeof(Rgb) * std::size_t(w);
    Imf::FrameBuffer fb;
    fb.insert("R", Imf::Slice(Imf::FLOAT, base + offsetof(Rgb, r), xs, ys));
    fb.insert("G", Imf::Slice(Imf::FLOAT, base + offsetof(Rgb, g), xs, ys));
    fb.insert("B", Imf::Slice(Imf::FLOAT, base + offsetof(Rgb, b), xs, ys));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return image;
  } catch (const std::exception& e) {
    throw Error(path.string() + ": cannot read EXR: " + e.what());
  }
}

}  // namespace

float linear_to_srgb(float v) {
  if (!(v > 0)) return 0;  // also maps NaN to black
  if (v >= 1) return 1;
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
}

unsigned char to_byte(float v) { return byte_of(v); }

bool is_supported_image_extension(const fs::path& path) {
  const std::string ext = lower_extension(path);
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".ppm" || ext == ".pfm" || ext == ".exr";
}

void write_image(const Image& image, const fs::path& path, const WriteOptions& options) {
  // (Callers that did not ask check_output_path first — the library, Python — get its message,
  // not the encoder's failure.)
  if (!is_supported_image_extension(path))
    throw Error(path.string() + ": unknown image format '" + path.extension().string() +
                "' (use .png, .jpg/.jpeg, .ppm, .pfm or .exr)");
  check_image_size(path, image.width(), image.height());
  OutputFile out(path);  // removed again unless committed
  write_by_extension(image, out, path, lower_extension(path), options.linear);
  out.commit();
}

void check_image_size(const fs::path& path, int width, int height) {
  const std::string ext = lower_extension(path);
  const auto refuse = [&](const std::string& limit) {
    throw Error(path.string() + ": " + limit + ", not " + std::to_string(width) + "x" + std::to_string(height));
  };
  if (width < 1 || height < 1) refuse("an image needs at least one pixel");
  const long long w = width, h = height;
  if ((ext == ".jpg" || ext == ".jpeg") && (w > kMaxJpegSide || h > kMaxJpegSide))
    refuse("a JPEG image holds at most 65535 pixels per side");
  if (ext == ".exr") return;
  if (w > kMaxImageSide || h > kMaxImageSide)
    refuse("a " + ext.substr(1) + " image can be read back with at most 16777216 pixels per side");
  if (ext == ".png" && (3 * w + 1) * h > kMaxPngBytes) refuse("a PNG image holds at most 2^30 bytes of rows, (3 x width + 1) x height");
  if (ext == ".ppm" && 3 * w * h > kMaxPpmBytes) refuse("a PPM image can be read back with at most 2^31 - 1 bytes of pixels");
}

void check_output_path(const fs::path& target) {
  if (!is_supported_image_extension(target))
    throw Error(target.string() + ": unknown image format '" + target.extension().string() +
                "' (use .png, .jpg/.jpeg, .ppm, .pfm or .exr)");
  // Where a symbolic link leads: the file that will be written (the link stays).
  const fs::path path = OutputFile::output_destination(target);
  const std::string name = path == target ? target.string() : target.string() + " (-> " + path.string() + ")";
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw Error(name + ": cannot write the image: it is a directory");
    if (!S_ISREG(st.st_mode) && !S_ISLNK(st.st_mode))
      throw Error(name + ": cannot write the image: it exists and is not a regular file");
  } else if (errno != ENOENT && errno != ENOTDIR) {  // ENOTDIR: the directory check below says which
    throw Error(name + ": cannot write the image: " + system_reason(errno));
  }
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (::stat(dir.c_str(), &st) != 0) {
    if (errno == ENOENT) throw Error(name + ": directory '" + dir.string() + "' does not exist");
    throw Error(name + ": cannot reach directory '" + dir.string() + "': " + system_reason(errno));
  }
  if (!S_ISDIR(st.st_mode)) throw Error(name + ": '" + dir.string() + "' is not a directory");
  // A file with the very name the image's temporary file will have: this also finds names too
  // long for the directory's file system (the temporary name is the longest one written).
  for (std::uint32_t serial = 0xffffffffu;; --serial) {
    const fs::path probe = OutputFile::temporary_name(path, serial);
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd >= 0) {
      ::close(fd);
      ::unlink(probe.c_str());
      return;
    }
    if (errno != EEXIST || serial < 0xffffff00u)
      throw Error(name + ": cannot write in directory '" + dir.string() + "': " + system_reason(errno));
  }
}

namespace {

// stb_image's RGB pixels (8 or 16 bit, freed here) as values / 255 or / 65535.
Image from_stb(void* pixels, int w, int h, bool sixteen, const std::string& name) {
  std::unique_ptr<void, void (*)(void*)> data(pixels, stbi_image_free);
  if (!data) throw Error(name + ": cannot read image: " + stbi_failure_reason());
  Image image(w, h);
  const float scale = sixteen ? 1.0f / 65535.0f : 1.0f / 255.0f;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = (std::size_t(y) * w + x) * 3;
      const auto v = [&](std::size_t k) {
        return sixteen ? float(static_cast<const unsigned short*>(data.get())[i + k]) * scale
                       : float(static_cast<const unsigned char*>(data.get())[i + k]) * scale;
      };
      image.at(x, y) = Rgb{v(0), v(1), v(2)};
    }
  return image;
}

}  // namespace

Image read_image(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw Error(path.string() + ": no such file");
  const std::string ext = lower_extension(path);
  if (ext == ".pfm") return read_pfm(path);
  if (ext == ".exr") return read_exr(path);
  int w = 0, h = 0, n = 0;
  const bool sixteen = stbi_is_16_bit(path.c_str());
  void* pixels = sixteen ? static_cast<void*>(stbi_load_16(path.c_str(), &w, &h, &n, 3))
                         : static_cast<void*>(stbi_load(path.c_str(), &w, &h, &n, 3));
  return from_stb(pixels, w, h, sixteen, path.string());  // (after the load has set w and h)
}

Image decode_image(std::string_view bytes, const std::string& name) {
  if (bytes.size() > std::size_t(std::numeric_limits<int>::max())) throw Error(name + ": the image is too large");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = int(bytes.size());
  int w = 0, h = 0, n = 0;
  // (Its size first: a few bytes of a compressed image must not ask for gigabytes.)
  if (!stbi_info_from_memory(data, size, &w, &h, &n)) throw Error(name + ": cannot read image: " + stbi_failure_reason());
  if (std::int64_t(w) * h > kMaxDecodedPixels)
    throw Error(name + ": the image has " + std::to_string(w) + " x " + std::to_string(h) + " pixels, more than " +
                std::to_string(kMaxDecodedPixels));
  const bool sixteen = stbi_is_16_bit_from_memory(data, size);
  void* pixels = sixteen ? static_cast<void*>(stbi_load_16_from_memory(data, size, &w, &h, &n, 3))
                         : static_cast<void*>(stbi_load_from_memory(data, size, &w, &h, &n, 3));
  return from_stb(pixels, w, h, sixteen, name);
}

}  // namespace strahl
