#pragma once
// Image comparison: root-mean-square error and PSNR over all channels.

#include "strahl/image/image.h"

namespace strahl {

// Throws strahl::Error when the sizes differ.
double rmse(const Image& a, const Image& b);
double psnr(const Image& a, const Image& b, double peak = 1.0);

}  // namespace strahl
