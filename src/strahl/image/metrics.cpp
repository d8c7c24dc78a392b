#include "strahl/image/metrics.h"

#include <cmath>
#include <limits>
#include <string>

#include "strahl/util/error.h"

namespace strahl {

double rmse(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height())
    throw Error("images differ in size: " + std::to_string(a.width()) + "x" + std::to_string(a.height()) + " vs " +
                std::to_string(b.width()) + "x" + std::to_string(b.height()));
  double sum = 0;
  for (std::size_t i = 0; i < a.pixels().size(); ++i) {
    const Rgb &p = a.pixels()[i], &q = b.pixels()[i];
    sum += double(p.r - q.r) * (p.r - q.r) + double(p.g - q.g) * (p.g - q.g) + double(p.b - q.b) * (p.b - q.b);
  }
  const double n = 3.0 * double(a.pixels().size());
  return n > 0 ? std::sqrt(sum / n) : 0.0;
}

double psnr(const Image& a, const Image& b, double peak) {
  const double e = rmse(a, b);
  return e > 0 ? 20.0 * std::log10(peak / e) : std::numeric_limits<double>::infinity();
}

}  // namespace strahl
