#include "display.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "strahl/image/image_io.h"

namespace strahl::view {

namespace {

// sRGB bytes of linear values in [0, 1], in 16384 steps (the exact conversion is a pow() per
// channel, too slow to run on every refresh).
constexpr int kLutSize = 16384;
const std::array<std::uint8_t, kLutSize + 1>& srgb_lut() {
  static const std::array<std::uint8_t, kLutSize + 1> lut = [] {
    std::array<std::uint8_t, kLutSize + 1> t{};
    for (int i = 0; i <= kLutSize; ++i) t[std::size_t(i)] = to_byte(linear_to_srgb(float(i) / kLutSize));
    return t;
  }();
  return lut;
}

std::uint8_t srgb(float v) {
  if (!(v > 0)) return 0;  // NaN too
  if (v >= 1) return 255;
  return srgb_lut()[std::size_t(v * kLutSize + 0.5f)];
}

std::uint8_t unit(float v) {
  if (!(v > 0)) return 0;
  return v >= 1 ? 255 : std::uint8_t(v * 255 + 0.5f);
}

Rgb id_colour(float id) {
  if (id < 0) return {};
  // A well-spread hue per id (golden-ratio steps), fully saturated.
  const float h = std::fmod(float(id) * 0.618034f, 1.0f) * 6;
  const float f = h - std::floor(h);
  switch (int(h)) {
    case 0: return {1, f, 0};
    case 1: return {1 - f, 1, 0};
    case 2: return {0, 1, f};
    case 3: return {0, 1 - f, 1};
    case 4: return {f, 0, 1};
    default: return {1, 0, 1 - f};
  }
}

}  // namespace

void to_display(const Image& image, Display display, double exposure, Rgba8Image& out) {
  out.width = image.width();
  out.height = image.height();
  out.bytes.resize(std::size_t(out.width) * std::size_t(out.height) * 4);
  const float gain = float(std::exp2(exposure));
  float far = 0;
  if (display == Display::Depth)
    for (const Rgb& p : image.pixels())
      if (std::isfinite(p.r)) far = std::max(far, p.r);
  std::uint8_t* o = out.bytes.data();
  for (const Rgb& p : image.pixels()) {
    switch (display) {
      case Display::Beauty: o[0] = srgb(p.r * gain); o[1] = srgb(p.g * gain); o[2] = srgb(p.b * gain); break;
      case Display::Albedo: o[0] = srgb(p.r); o[1] = srgb(p.g); o[2] = srgb(p.b); break;
      case Display::Normal: o[0] = unit((p.r + 1) / 2); o[1] = unit((p.g + 1) / 2); o[2] = unit((p.b + 1) / 2); break;
      case Display::Depth: {
        const std::uint8_t g = std::isfinite(p.r) && far > 0 ? unit(1 - p.r / far * 0.9f) : 0;
        o[0] = o[1] = o[2] = g;
        break;
      }
      case Display::Id: {
        const Rgb c = id_colour(p.r);
        o[0] = unit(c.r); o[1] = unit(c.g); o[2] = unit(c.b);
        break;
      }
    }
    o[3] = 255;
    o += 4;
  }
}

}  // namespace strahl::view
