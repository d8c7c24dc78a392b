#pragma once
// Checks shared by compile() (for scenes built in C++) and the scene-file loaders (which point
// at the offending value's line and column). Each throws strahl::Error.

#include <cmath>
#include <cstddef>
#include <string>

#include "strahl/shading/material.h"
#include "strahl/util/error.h"
#include "strahl/util/number_syntax.h"

namespace strahl::validate {

// A number in a message: the shortest text that reads back as exactly v (0.5, -1, 1048576,
// 1e-300), never a rounded 1.04858e+06.
inline std::string str(Real v) { return number::shortest(v); }

// The scales strahl renders alike (docs/scene-format.md, "Units and scale"): every coordinate
// within ±kMaxCoordinate and every length (radius, edge, distance, size) in [kMinLength,
// kMaxCoordinate]. Inside, squares and products of lengths (areas, |cross|², r²) stay far from
// double's overflow and underflow and coordinates fit the accelerators' float boxes; the lecture
// scene scaled by 10^k renders the same image for every k in [−kMaxScaleExponent,
// kMaxScaleExponent] (tests/scale_test.cpp sweeps them all).
inline constexpr Real kMaxCoordinate = 1e32;
inline constexpr Real kMinLength = 1e-32;
inline constexpr int kMaxScaleExponent = 30;
inline const std::string kScaleLimits = "(scenes must fit within 1e-32 to 1e32 units: docs/scene-format.md, \"Units and scale\")";

inline void finite(Real v, const FileLoc& loc, const std::string& what) {
  if (!std::isfinite(v)) throw Error(loc, what + " must be a finite number");
}
inline void finite(const Vec3& v, const FileLoc& loc, const std::string& what) {
  if (!is_finite(v)) throw Error(loc, what + " must have finite components");
}
inline void positive(Real v, const FileLoc& loc, const std::string& what) {
  finite(v, loc, what);
  if (!(v > 0)) throw Error(loc, what + " must be positive (got " + str(v) + ")");
}
inline void non_negative(Real v, const FileLoc& loc, const std::string& what) {
  finite(v, loc, what);
  if (v < 0) throw Error(loc, what + " must not be negative (got " + str(v) + ")");
}
inline void in_range(Real v, Real lo, Real hi, const FileLoc& loc, const std::string& what) {
  finite(v, loc, what);
  if (v < lo || v > hi)
    throw Error(loc, what + " must lie in [" + str(lo) + ", " + str(hi) + "] (got " +
                         str(v) + ")");
}
inline void non_negative(const Vec3& v, const FileLoc& loc, const std::string& what) {
  finite(v, loc, what);
  if (v.x < 0 || v.y < 0 || v.z < 0) throw Error(loc, what + " must not have negative components");
}
inline void non_zero(const Vec3& v, const FileLoc& loc, const std::string& what) {
  finite(v, loc, what);
  if (max_abs_component(v) == 0) throw Error(loc, what + " must not be the zero vector");  // (not |v|², which underflows)
}
// A point: finite, and no coordinate beyond ±kMaxCoordinate.
inline void coordinates(const Vec3& v, const FileLoc& loc, const std::string& what) {
  finite(v, loc, what);
  const Real m = max_abs_component(v);
  if (m > kMaxCoordinate) throw Error(loc, what + " has a coordinate of " + str(m) + ", beyond ±1e32 " + kScaleLimits);
}
inline void coordinate(Real v, const FileLoc& loc, const std::string& what) {
  finite(v, loc, what);
  if (std::fabs(v) > kMaxCoordinate) throw Error(loc, what + " " + str(v) + " lies beyond ±1e32 " + kScaleLimits);
}
// A length: positive, at least kMinLength and at most kMaxCoordinate.
inline void length(Real v, const FileLoc& loc, const std::string& what) {
  finite(v, loc, what);
  if (!(v > 0)) throw Error(loc, what + " must be positive (got " + str(v) + ")");
  if (v < kMinLength) throw Error(loc, what + " " + str(v) + " is below 1e-32, the smallest length " + kScaleLimits);
  if (v > kMaxCoordinate) throw Error(loc, what + " " + str(v) + " is above 1e32, the largest length " + kScaleLimits);
}

// A shape's size against its distance from the origin: below about 1e4 ulps of double there
// (1e-12 of the coordinates) rounding of hit points and of the shape itself is comparable to the
// shape: it may be missed or hit at the wrong place. Refused, naming both. (Shapes smaller than
// the secondary-ray offset, kRayEpsilon·|p|, still render, with refraction through them skipped.)
inline constexpr Real kMinRelativeSize = Real(1e-12);
inline void resolvable(Real size, Real position, const FileLoc& loc, const std::string& what) {
  if (size < kMinRelativeSize * position)
    throw Error(loc, what + " " + str(size) + " is too small for its distance from the origin (" + str(position) +
                         "): sizes must be at least 1e-12 of the coordinates, double's precision there");
}

// v/|v| without overflow or underflow of |v|² (a direction given as (0, 1e-300, 0) or (1e200, 0, 0)).
// (Divided component by component: v / m multiplies by 1/m, which is infinite for a denormal m.)
inline Vec3 over_largest(const Vec3& v) {
  const Real m = max_abs_component(v);
  return {v.x / m, v.y / m, v.z / m};
}
inline Vec3 direction(const Vec3& v) { return normalize(over_largest(v)); }
// |v| likewise (0 for the zero vector).
inline Real norm(const Vec3& v) {
  const Real m = max_abs_component(v);
  return m > 0 ? length(over_largest(v)) * m : Real(0);
}

inline void int_range(long v, long lo, long hi, const FileLoc& loc, const std::string& what) {
  // Whole numbers in full ("[1, 1048576]", not "1.04858e+06").
  if (v < lo || v > hi)
    throw Error(loc, what + " must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                         std::to_string(v) + ")");
}

// `textures`: how many image textures the scene has (Material::texture must name one of them);
// kTexturesUnknown where a material is made before its scene (compile() checks it then).
inline constexpr std::size_t kTexturesUnknown = ~std::size_t(0);
inline void material(const Material& m, std::size_t textures, const FileLoc& loc) {
  non_negative(m.color, loc, "material colour");
  non_negative(m.ambient, loc, "ambient");
  non_negative(m.diffuse, loc, "diffuse");
  non_negative(m.specular, loc, "specular");
  non_negative(m.shininess, loc, "shininess");
  in_range(m.reflectivity, 0, 1, loc, "reflectivity");
  in_range(m.transparency, 0, 1, loc, "transparency");
  positive(m.ior, loc, "ior");
  non_negative(m.checker_size, loc, "checker size");
  if (m.checker_size > 0) length(m.checker_size, loc, "checker size");
  non_negative(m.checker_color, loc, "checker colour");
  non_negative(m.emission, loc, "emission");
  if (m.texture != kNoTexture && m.texture >= textures)
    throw Error(loc, "material texture " + std::to_string(m.texture) + " does not exist (the scene has " +
                         std::to_string(textures) + ")");
  if (m.texture != kNoTexture && m.checker_size > 0) throw Error(loc, "a material has a checker or an image, not both");
}

}  // namespace strahl::validate
