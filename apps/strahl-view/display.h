#pragma once
// From the renderer's linear image (or AOV) to the window's 8-bit RGBA pixels: exposure, sRGB,
// and a false-colour mapping for each AOV. For the screen only: saved images go through the
// usual writers (image/image_io.h), unchanged by exposure.

#include <cstdint>
#include <vector>

#include "strahl/image/image.h"
#include "view_renderer.h"

namespace strahl::view {

// Pixels as R, G, B, A bytes, row 0 at the top.
struct Rgba8Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> bytes;
};

//   image   linear radiance × 2^exposure, sRGB encoded
//   depth   grey, 1 − depth / (the largest finite depth): near is bright, nothing hit is black
//   normal  (n + 1) / 2 per channel
//   albedo  the surface colour, sRGB encoded
//   id      a colour per object id, black where nothing is hit
void to_display(const Image& image, Display display, double exposure, Rgba8Image& out);

}  // namespace strahl::view
