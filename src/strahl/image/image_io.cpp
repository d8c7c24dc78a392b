#include "strahl/image/image_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <system_error>
#include <vector>

#include "strahl/util/error.h"

namespace strahl {
namespace fs = std::filesystem;

namespace {

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// 8-bit encoding, in parallel: the sRGB curve costs a pow per channel (~0.1 s at 1080p).
std::vector<unsigned char> to_bytes(const Image& image, bool linear) {
  const std::vector<Rgb>& pixels = image.pixels();
  std::vector<unsigned char> bytes(pixels.size() * 3);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pixels.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Rgb& p = pixels[i];
      bytes[3 * i + 0] = to_byte(linear ? p.r : linear_to_srgb(p.r));
      bytes[3 * i + 1] = to_byte(linear ? p.g : linear_to_srgb(p.g));
      bytes[3 * i + 2] = to_byte(linear ? p.b : linear_to_srgb(p.b));
    }
  });
  return bytes;
}

void write_ppm(const Image& image, const fs::path& path, bool linear) {
  std::ofstream out(path, std::ios::binary);
  out << "P6\n" << image.width() << ' ' << image.height() << "\n255\n";
  const std::vector<unsigned char> bytes = to_bytes(image, linear);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!out) throw Error(path.string() + ": cannot write");
}

// Portable float map: little-endian (negative scale), rows from the bottom up.
void write_pfm(const Image& image, const fs::path& path) {
  std::ofstream out(path, std::ios::binary);
  out << "PF\n" << image.width() << ' ' << image.height() << "\n-1.0\n";
  for (int row = image.height() - 1; row >= 0; --row) {
    for (int x = 0; x < image.width(); ++x) {
      const Rgb& p = image.at(x, row);
      const float v[3] = {p.r, p.g, p.b};
      out.write(reinterpret_cast<const char*>(v), sizeof v);
    }
  }
  if (!out) throw Error(path.string() + ": cannot write");
}

void write_exr(const Image& image, const fs::path& path) {
  try {
    Imf::Header header(image.width(), image.height());
    for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(path.c_str(), header);
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

void write_by_extension(const Image& image, const fs::path& path, const std::string& ext, bool linear) {
  if (ext == ".pfm") return write_pfm(image, path);
  if (ext == ".exr") return write_exr(image, path);
  if (ext == ".ppm") return write_ppm(image, path, linear);
  const std::vector<unsigned char> bytes = to_bytes(image, linear);
  int ok = 0;
  stbi_write_png_compression_level = 4;  // stb's default (8) costs twice the time for ~5% smaller files
  if (ext == ".png") ok = stbi_write_png(path.c_str(), image.width(), image.height(), 3, bytes.data(), image.width() * 3);
  if (ext == ".jpg" || ext == ".jpeg") ok = stbi_write_jpg(path.c_str(), image.width(), image.height(), 3, bytes.data(), 95);
  if (!ok) throw Error(path.string() + ": cannot write");
}

Image read_pfm(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int w = 0, h = 0;
  double scale = 0;
  in >> magic >> w >> h >> scale;
  in.get();
  if (!in || (magic != "PF" && magic != "Pf") || w <= 0 || h <= 0 || w > 1 << 16 || h > 1 << 16)
    throw Error(path.string() + ": not a valid PFM file");
  const int channels = magic == "PF" ? 3 : 1;
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

unsigned char to_byte(float v) {
  if (!(v > 0)) return 0;
  if (v >= 1) return 255;
  return static_cast<unsigned char>(std::lround(v * 255.0f));
}

bool is_supported_image_extension(const fs::path& path) {
  const std::string ext = lower_extension(path);
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".ppm" || ext == ".pfm" || ext == ".exr";
}

void write_image(const Image& image, const fs::path& path, const WriteOptions& options) {
  if (!is_supported_image_extension(path))
    throw Error(path.string() + ": unknown image format '" + path.extension().string() +
                "' (use .png, .jpg/.jpeg, .ppm, .pfm or .exr)");
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(path.string() + ": directory '" + dir.string() + "' does not exist");
  static std::atomic<int> counter{0};
  fs::path tmp = path;
  tmp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  try {
    write_by_extension(image, tmp, lower_extension(path), options.linear);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error(path.string() + ": cannot write: " + ec.message());
  }
}

void check_output_path(const fs::path& path) {
  if (!is_supported_image_extension(path))
    throw Error(path.string() + ": unknown image format '" + path.extension().string() +
                "' (use .png, .jpg/.jpeg, .ppm, .pfm or .exr)");
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(path, ec);
  if (fs::is_directory(st)) throw Error(path.string() + ": cannot write the image: it is a directory");
  if (fs::exists(st) && !fs::is_regular_file(st) && !fs::is_symlink(st))
    throw Error(path.string() + ": cannot write the image: it exists and is not a regular file");
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec)) throw Error(path.string() + ": directory '" + dir.string() + "' does not exist");
  std::string probe = (dir / ".strahl-write-test-XXXXXX").string();
  const int fd = ::mkstemp(probe.data());
  if (fd < 0)
    throw Error(path.string() + ": cannot write in directory '" + dir.string() + "': " +
                std::error_code(errno, std::generic_category()).message());
  ::close(fd);
  fs::remove(probe, ec);
}

Image read_image(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw Error(path.string() + ": no such file");
  const std::string ext = lower_extension(path);
  if (ext == ".pfm") return read_pfm(path);
  if (ext == ".exr") return read_exr(path);
  int w = 0, h = 0, n = 0;
  const bool sixteen = stbi_is_16_bit(path.c_str());
  std::unique_ptr<void, void (*)(void*)> data(
      sixteen ? static_cast<void*>(stbi_load_16(path.c_str(), &w, &h, &n, 3))
              : static_cast<void*>(stbi_load(path.c_str(), &w, &h, &n, 3)),
      stbi_image_free);
  if (!data) throw Error(path.string() + ": cannot read image: " + stbi_failure_reason());
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

}  // namespace strahl
