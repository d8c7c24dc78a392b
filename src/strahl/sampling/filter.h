#pragma once
// Reconstruction filters (pbrt 4th ed., 8.8): a pixel's value is Σ f(x − x_i) L_i / Σ f(x − x_i)
// over the samples within the filter's radius of its centre. Filters are separable,
// f(dx, dy) = f(dx) f(dy), with the support −r ≤ d < r (half open, so that a box of radius 0.5
// gives each sample to exactly one pixel).

#include <cmath>
#include <cstdint>

#include "strahl/math/config.h"

namespace strahl {

enum class FilterKind : std::uint8_t { Box, Tent, Gaussian, Mitchell };

struct Filter {
  FilterKind kind = FilterKind::Box;
  Real radius = Real(0.5);  // in pixels, 0.5 .. 4
};

inline constexpr Real kMinFilterRadius = Real(0.5), kMaxFilterRadius = Real(4);

// Gaussian: σ = r/3, shifted down so that it reaches 0 at the radius.
STRAHL_HOST_DEVICE inline Real gaussian_alpha(Real radius) { return Real(4.5) / (radius * radius); }

// Mitchell–Netravali with B = C = 1/3 on t = 2|x|/r ∈ [0, 2).
STRAHL_HOST_DEVICE inline Real mitchell_1d(Real t) {
  constexpr Real B = Real(1) / 3, C = Real(1) / 3;
  t = std::fabs(t);
  if (t < 1) return ((12 - 9 * B - 6 * C) * t * t * t + (-18 + 12 * B + 6 * C) * t * t + (6 - 2 * B)) / 6;
  if (t < 2)
    return ((-B - 6 * C) * t * t * t + (6 * B + 30 * C) * t * t + (-12 * B - 48 * C) * t + (8 * B + 24 * C)) / 6;
  return 0;
}

// f(x) for one axis; 0 outside −r ≤ x < r.
STRAHL_HOST_DEVICE inline Real filter_1d(const Filter& f, Real x) {
  const Real r = f.radius;
  if (!(x >= -r && x < r)) return 0;
  switch (f.kind) {
    case FilterKind::Box: return 1;
    case FilterKind::Tent: return 1 - std::fabs(x) / r;
    case FilterKind::Gaussian: {
      const Real a = gaussian_alpha(r);
      return std::fmax(Real(0), std::exp(-a * x * x) - std::exp(-a * r * r));
    }
    case FilterKind::Mitchell: return mitchell_1d(2 * x / r);
  }
  return 0;
}

STRAHL_HOST_DEVICE inline Real filter_weight(const Filter& f, Real dx, Real dy) {
  return filter_1d(f, dx) * filter_1d(f, dy);
}

// ∫ f(x) dx over the support, in closed form (the Mitchell kernel integrates to 1 on t).
STRAHL_HOST_DEVICE inline Real filter_integral_1d(const Filter& f) {
  const Real r = f.radius;
  switch (f.kind) {
    case FilterKind::Box: return 2 * r;
    case FilterKind::Tent: return r;
    case FilterKind::Gaussian: {
      const Real a = gaussian_alpha(r);
      return std::sqrt(kPi / a) * std::erf(std::sqrt(a) * r) - 2 * r * std::exp(-a * r * r);
    }
    case FilterKind::Mitchell: return r / 2;
  }
  return 0;
}

// Only box filters of radius ≤ 0.5 keep every sample inside its own pixel.
STRAHL_HOST_DEVICE inline bool filter_is_pixel_local(const Filter& f) {
  return f.kind == FilterKind::Box && f.radius <= Real(0.5);
}

}  // namespace strahl
