#pragma once
// What strahl-diff measures between two images of the same size (docs/cli.md, "strahl-diff").

#include <cstddef>

#include "strahl/image/image.h"

namespace strahl::diff {

struct Comparison {
  double rmse = 0;  // over all channels; NaN when some value is not finite
  double psnr = 0;  // 20·log10(1/rmse): +inf for identical images, NaN with rmse
  double max = 0;   // largest difference in one channel; NaN when some value is not finite
  std::size_t differing = 0;   // pixels with a channel differing by more than 1/255 (or not finite)
  std::size_t non_finite[2] = {0, 0};  // NaN or infinite channel values in A and in B
  Image difference;  // |A − B| × 10 per channel; 10 where a value is not finite
};

// Finite values are clamped to 0 … 1 first, as an 8-bit file would store them. A channel with a
// NaN or an infinity in either image counts as different by an unknown amount, NaN, so that rmse,
// psnr and max become NaN: such a pair never passes a threshold. Throws strahl::Error when the
// sizes differ.
Comparison compare(const Image& a, const Image& b);

}  // namespace strahl::diff
