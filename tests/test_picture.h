#pragma once
// The image textures' test picture (tests/image_texture_test.cpp, tests/mesh_uv_test.cpp): 4 × 2
// pixels, every one different, of dyadic values (so that bilinear blends are exact).

#include <memory>

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

}  // namespace strahl::test
