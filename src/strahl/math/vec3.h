#pragma once
// A 3-vector of Real used for points, directions and linear RGB colours.

#include <cmath>

#include "strahl/math/config.h"

namespace strahl {

struct Vec3 {
  Real x = 0, y = 0, z = 0;

  constexpr Vec3() = default;
  STRAHL_HOST_DEVICE constexpr explicit Vec3(Real s) : x(s), y(s), z(s) {}
  STRAHL_HOST_DEVICE constexpr Vec3(Real x_, Real y_, Real z_) : x(x_), y(y_), z(z_) {}

  STRAHL_HOST_DEVICE constexpr Real operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  STRAHL_HOST_DEVICE constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  STRAHL_HOST_DEVICE constexpr Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
  STRAHL_HOST_DEVICE constexpr Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
  STRAHL_HOST_DEVICE constexpr Vec3& operator*=(Real s) { x *= s; y *= s; z *= s; return *this; }

  // The lecture's spelling, so its snippets read as they are written.
  STRAHL_HOST_DEVICE constexpr Real dot(const Vec3& o) const { return x * o.x + y * o.y + z * o.z; }
  STRAHL_HOST_DEVICE Real length() const { return std::sqrt(dot(*this)); }
  STRAHL_HOST_DEVICE Vec3 normalize() const { const Real inv = Real(1) / length(); return {x * inv, y * inv, z * inv}; }
};

STRAHL_HOST_DEVICE constexpr Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
STRAHL_HOST_DEVICE constexpr Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
STRAHL_HOST_DEVICE constexpr Vec3 operator*(const Vec3& a, const Vec3& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
STRAHL_HOST_DEVICE constexpr Vec3 operator*(const Vec3& a, Real s) { return {a.x * s, a.y * s, a.z * s}; }
STRAHL_HOST_DEVICE constexpr Vec3 operator*(Real s, const Vec3& a) { return {a.x * s, a.y * s, a.z * s}; }
STRAHL_HOST_DEVICE constexpr Vec3 operator/(const Vec3& a, Real s) { return a * (Real(1) / s); }
STRAHL_HOST_DEVICE constexpr bool operator==(const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

STRAHL_HOST_DEVICE constexpr Real dot(const Vec3& a, const Vec3& b) { return a.dot(b); }
STRAHL_HOST_DEVICE constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
STRAHL_HOST_DEVICE constexpr Real length_squared(const Vec3& a) { return dot(a, a); }
STRAHL_HOST_DEVICE inline Real length(const Vec3& a) { return a.length(); }
STRAHL_HOST_DEVICE inline Vec3 normalize(const Vec3& a) { return a.normalize(); }
STRAHL_HOST_DEVICE constexpr Real max_component(const Vec3& a) {
  return a.x > a.y ? (a.x > a.z ? a.x : a.z) : (a.y > a.z ? a.y : a.z);
}
STRAHL_HOST_DEVICE inline Real max_abs_component(const Vec3& a) {
  return max_component(Vec3(std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)));
}
STRAHL_HOST_DEVICE inline bool is_finite(const Vec3& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
STRAHL_HOST_DEVICE constexpr bool is_black(const Vec3& a) { return a.x == 0 && a.y == 0 && a.z == 0; }
// Component-wise min/max. Plain comparisons rather than fmin/fmax, which GCC compiles to libm
// calls (for their NaN rules) and which made up 14% of a BVH build; inputs here are finite.
STRAHL_HOST_DEVICE constexpr Vec3 min(const Vec3& a, const Vec3& b) {
  return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z};
}
STRAHL_HOST_DEVICE constexpr Vec3 max(const Vec3& a, const Vec3& b) {
  return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z};
}

}  // namespace strahl
