#pragma once
// The image textures' test picture (tests/image_texture_test.cpp, tests/mesh_uv_test.cpp): 4 × 2
// pixels, every one different, of dyadic values (so that bilinear blends are exact); and a tiny
// 8-bit picture file for the readers of mesh files' materials (gltf_test, obj_materials_test).

#include <cmath>
#include <memory>
#include <string>

#include "strahl/image/image.h"
#include "strahl/math/vec3.h"

namespace strahl::test {

inline constexpr int kPictureWidth = 4, kPictureHeight = 2;

// Pixel (x, row) of the test picture (row 0 the top).
inline Vec3 picture_pixel(int x, int row) { return {x * 0.25, row * 0.5, 0.0625 * (1 + x + kPictureWidth * row)}; }

inline std::shared_ptr<const Image> picture() {
  auto image = std::make_shared<Image>(kPictureWidth, kPictureHeight);
  for (int row = 0; row < kPictureHeight; ++row)
    for (int x = 0; x < kPictureWidth; ++x) {
      const Vec3 c = picture_pixel(x, row);
      image->at(x, row) = {float(c.x), float(c.y), float(c.z)};
    }
  return image;
}

// A 2 × 1 binary PPM (stb_image reads it as it reads a PNG): (64, 128, 255) and (255, 0, 32).
inline const std::string kPpm = std::string("P6\n2 1\n255\n") + std::string("\x40\x80\xff\xff\x00\x20", 6);

// An 8-bit code decoded from sRGB, as pictures are read (IEC 61966-2-1), in double.
inline double srgb_code(int code) {
  const double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

}  // namespace strahl::test
