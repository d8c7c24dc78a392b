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

// The Gaussian's value at the radius, which it is shifted down by; 0 for the other filters.
STRAHL_HOST_DEVICE inline Real filter_edge(const Filter& f) {
  if (f.kind != FilterKind::Gaussian) return 0;
  const Real a = gaussian_alpha(f.radius);
  return std::exp(-a * f.radius * f.radius);
}

// f(x) of a filter of kind K and radius r for −r ≤ x < r; `edge`: filter_edge(f).
template <FilterKind K>
STRAHL_HOST_DEVICE inline Real filter_of_kind([[maybe_unused]] Real x, [[maybe_unused]] Real r, [[maybe_unused]] Real edge) {
  if constexpr (K == FilterKind::Box) return 1;
  else if constexpr (K == FilterKind::Tent) return 1 - std::fabs(x) / r;
  else if constexpr (K == FilterKind::Gaussian) {
    // fmax(0, g) without the library call (g is never −0, a NaN gives 0 as fmax does).
    const Real g = std::exp(-gaussian_alpha(r) * x * x) - edge;
    return g > 0 ? g : Real(0);
  }
  else return mitchell_1d(2 * x / r);
}

// filter_of_kind<K>(c − (Real(p0 + i) + 0.5)) into w[i] for i < count, 0 outside the support:
// the weights of a sample at film coordinate c for the pixels p0 … p0 + count − 1 along one axis.
template <FilterKind K>
STRAHL_HOST_DEVICE inline void filter_weights_of_kind(Real r, Real edge, Real c, int p0, int count, Real* w) {
  for (int i = 0; i < count; ++i) {
    const Real x = c - (Real(p0 + i) + Real(0.5));
    w[i] = x >= -r && x < r ? filter_of_kind<K>(x, r, edge) : Real(0);
  }
}

// The same for any filter, its kind chosen once for the row.
STRAHL_HOST_DEVICE inline void filter_weights_1d(const Filter& f, Real edge, Real c, int p0, int count, Real* w) {
  switch (f.kind) {
    case FilterKind::Box: return filter_weights_of_kind<FilterKind::Box>(f.radius, edge, c, p0, count, w);
    case FilterKind::Tent: return filter_weights_of_kind<FilterKind::Tent>(f.radius, edge, c, p0, count, w);
    case FilterKind::Gaussian: return filter_weights_of_kind<FilterKind::Gaussian>(f.radius, edge, c, p0, count, w);
    case FilterKind::Mitchell: return filter_weights_of_kind<FilterKind::Mitchell>(f.radius, edge, c, p0, count, w);
  }
  for (int i = 0; i < count; ++i) w[i] = 0;
}

// f(x) for one axis; 0 outside −r ≤ x < r.
STRAHL_HOST_DEVICE inline Real filter_1d(const Filter& f, Real x) {
  const Real r = f.radius;
  if (!(x >= -r && x < r)) return 0;
  switch (f.kind) {
    case FilterKind::Box: return filter_of_kind<FilterKind::Box>(x, r, 0);
    case FilterKind::Tent: return filter_of_kind<FilterKind::Tent>(x, r, 0);
    case FilterKind::Gaussian: return filter_of_kind<FilterKind::Gaussian>(x, r, filter_edge(f));
    case FilterKind::Mitchell: return filter_of_kind<FilterKind::Mitchell>(x, r, 0);
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
