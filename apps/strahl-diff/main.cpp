// strahl-diff A B: compares two images (PNG 8/16-bit, PPM, PFM, EXR) on 0..1 values:
// RMSE, PSNR, largest difference, all on values clamped to 0..1 as 8/16-bit files store them. Exit code 0, or 2 when an image cannot be read.

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "strahl/image/image_io.h"
#include "strahl/image/metrics.h"
#include "strahl/util/error.h"

namespace {
strahl::Image clamped(strahl::Image image) {
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      strahl::Rgb& p = image.at(x, y);
      for (float* c : {&p.r, &p.g, &p.b}) *c = std::clamp(*c, 0.0f, 1.0f);
    }
  return image;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    fmt::print(stderr, "usage: strahl-diff IMAGE_A IMAGE_B [DIFF_IMAGE]\n");
    return 1;
  }
  if (argc == 4 && !strahl::is_supported_image_extension(argv[3])) {
    fmt::print(stderr, "strahl-diff: error: {}: unknown image format\n", argv[3]);
    return 1;
  }
  try {
    const strahl::Image a = clamped(strahl::read_image(argv[1])), b = clamped(strahl::read_image(argv[2]));
    const double e = strahl::rmse(a, b);
    double worst = 0;
    long over = 0;
    strahl::Image diff(a.width(), a.height());
    for (std::size_t i = 0; i < a.pixels().size(); ++i) {
      const strahl::Rgb &p = a.pixels()[i], &q = b.pixels()[i];
      const double d = std::max({std::fabs(p.r - q.r), std::fabs(p.g - q.g), std::fabs(p.b - q.b)});
      worst = std::max(worst, d);
      over += d > 1.0 / 255;
      // |A − B| amplified 10×, so that differences of a few 1/255 show.
      diff.at(int(i % std::size_t(a.width())), int(i / std::size_t(a.width()))) =
          strahl::Rgb{10 * std::fabs(p.r - q.r), 10 * std::fabs(p.g - q.g), 10 * std::fabs(p.b - q.b)};
    }
    fmt::print("rmse {:.3e}  psnr {:.2f} dB  max {:.4f}  pixels differing by more than 1/255: {} of {}\n", e,
               strahl::psnr(a, b), worst, over, a.pixels().size());
    if (argc == 4) strahl::write_image(diff, argv[3], {true});
  } catch (const std::exception& err) {
    fmt::print(stderr, "strahl-diff: error: {}\n", err.what());
    return 2;
  }
  return 0;
}
