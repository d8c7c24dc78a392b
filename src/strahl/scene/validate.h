#pragma once
// Checks shared by compile() (for scenes built in C++) and the scene-file loaders (which point
// at the offending value's line and column). Each throws strahl::Error.

#include <cmath>
#include <sstream>
#include <string>

#include "strahl/shading/material.h"
#include "strahl/util/error.h"

namespace strahl::validate {

// Shortest readable form of a number for messages: 0.5, -1, 1e+06.
inline std::string str(Real v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

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
  if (length_squared(v) == 0) throw Error(loc, what + " must not be the zero vector");
}
inline void int_range(long v, long lo, long hi, const FileLoc& loc, const std::string& what) {
  // Whole numbers in full ("[1, 1048576]", not "1.04858e+06").
  if (v < lo || v > hi)
    throw Error(loc, what + " must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                         std::to_string(v) + ")");
}

inline void material(const Material& m, const FileLoc& loc) {
  non_negative(m.color, loc, "material colour");
  non_negative(m.ambient, loc, "ambient");
  non_negative(m.diffuse, loc, "diffuse");
  non_negative(m.specular, loc, "specular");
  non_negative(m.shininess, loc, "shininess");
  in_range(m.reflectivity, 0, 1, loc, "reflectivity");
  in_range(m.transparency, 0, 1, loc, "transparency");
  positive(m.ior, loc, "ior");
  non_negative(m.checker_size, loc, "checker size");
  non_negative(m.checker_color, loc, "checker colour");
}

}  // namespace strahl::validate
