#include "compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "strahl/util/error.h"

namespace strahl::diff {

Comparison compare(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height())
    throw Error("images differ in size: " + std::to_string(a.width()) + "x" + std::to_string(a.height()) + " vs " +
                std::to_string(b.width()) + "x" + std::to_string(b.height()));
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  Comparison c;
  c.difference = Image(a.width(), a.height());
  double sum = 0;
  for (std::size_t i = 0; i < a.pixels().size(); ++i) {
    const Rgb &p = a.pixels()[i], &q = b.pixels()[i];
    const float va[3] = {p.r, p.g, p.b}, vb[3] = {q.r, q.g, q.b};
    float shown[3];
    bool differs = false;
    for (int k = 0; k < 3; ++k) {
      const bool finite_a = std::isfinite(va[k]), finite_b = std::isfinite(vb[k]);
      c.non_finite[0] += !finite_a;
      c.non_finite[1] += !finite_b;
      if (!finite_a || !finite_b) {
        differs = true;
        shown[k] = 10;
        continue;
      }
      const double d = std::fabs(double(std::clamp(va[k], 0.0f, 1.0f)) - double(std::clamp(vb[k], 0.0f, 1.0f)));
      sum += d * d;
      c.max = std::max(c.max, d);
      differs = differs || d > 1.0 / 255;
      shown[k] = float(10 * d);  // amplified, so that differences of a few 1/255 show
    }
    c.differing += differs;
    c.difference.at(int(i % std::size_t(a.width())), int(i / std::size_t(a.width()))) = Rgb{shown[0], shown[1], shown[2]};
  }
  const bool all_finite = c.non_finite[0] == 0 && c.non_finite[1] == 0;
  const double n = 3.0 * double(a.pixels().size());
  c.rmse = !all_finite ? kNaN : n > 0 ? std::sqrt(sum / n) : 0.0;
  if (!all_finite) c.max = kNaN;
  c.psnr = std::isnan(c.rmse) ? kNaN : c.rmse > 0 ? 20.0 * std::log10(1.0 / c.rmse) : std::numeric_limits<double>::infinity();
  return c;
}

}  // namespace strahl::diff
