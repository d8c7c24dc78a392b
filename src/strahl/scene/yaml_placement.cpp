// Where a YAML scene's objects go (yaml_reader.h): scale, rotate, translate, a matrix or a transform
// list; and how they move (motion: velocity, keyframes, spin).

#include "strahl/scene/yaml_reader.h"

#include <cmath>
#include <string>

#include "strahl/scene/validate.h"

namespace strahl {

// `motion: {velocity: [x, y, z]}` or `motion: {from: {…}, to: {…}}`, each keyframe a transform
// as an object's placement is (scale/rotate/translate, a matrix or a transform list).
Transform YamlReader::transform(const YAML::Node& n, const std::string& what) const {
  map(n, what);
  keys(n, {"scale", "rotate", "translate", "matrix", "transform"}, what);
  return placement(n, "motion ");
}

// `spin: {axis: [x, y, z], angle: degrees, center: [x, y, z]}` (center optional) beside either,
// or alone.
Motion YamlReader::motion(const YAML::Node& n) const {
  map(n, "motion");
  keys(n, {"velocity", "from", "to", "spin"}, "motion");
  const Spin s = n["spin"] ? spin(n["spin"]) : Spin{};
  if (const auto v = n["velocity"]) {
    if (n["from"] || n["to"]) fail(v, "give either velocity or from/to keyframes, not both");
    return Motion::linear(vec3(v, "velocity")).with_spin(s);
  }
  if (!n["from"] && !n["to"]) {
    if (n["spin"]) return Motion::spinning(s);
    fail(n, "motion needs 'velocity', 'from'/'to' keyframes or a 'spin'");
  }
  const Transform from = n["from"] ? transform(n["from"], "motion from") : Transform{};
  const Transform to = n["to"] ? transform(n["to"], "motion to") : Transform{};
  return Motion::keyframes(from, to).with_spin(s);
}

Spin YamlReader::spin(const YAML::Node& n) const {
  map(n, "motion spin");
  keys(n, {"axis", "angle", "center"}, "motion spin");
  Spin s;
  const YAML::Node axis = required(n, "axis", "motion spin");
  s.axis = vec3(axis, "spin axis");
  if (s.axis == Vec3(0)) fail(axis, "spin axis must not be zero");
  s.angle = number(required(n, "angle", "motion spin"), "spin angle");
  if (const auto c = n["center"]) s.center = vec3(c, "spin center");
  return s;
}

// Where an object's own coordinates go (docs/scene-format.md, "Transforms"): the fixed-order
// keys `scale`, `rotate` ([x, y, z] degrees or {axis, angle}) and `translate`, or a `matrix`,
// or a `transform` list applied in the order written. `what` prefixes the zero-scale message.
Transform YamlReader::placement(const YAML::Node& n, const std::string& what) const {
  if (const YAML::Node list = n["transform"]) {
    for (const char* k : {"scale", "rotate", "translate", "matrix"})
      if (n[k]) fail(n[k], std::string("give either a transform list or '") + k + "', not both (put it in the list)");
    sequence(list, "transform");
    Mat3 m;
    Vec3 t(0);
    for (const YAML::Node& step : list) {
      if (!step.IsMap() || step.size() != 1)
        fail(step, "each step of a transform list must be a map of one key: scale, rotate, translate or matrix");
      const std::string key = step.begin()->first.Scalar();
      const YAML::Node v = step.begin()->second;
      Mat3 sm;
      Vec3 st(0);
      if (key == "scale") sm = Mat3::scale(scale(v, what));
      else if (key == "rotate") sm = rotation(v);
      else if (key == "translate") st = vec3(v, "translate");
      else if (key == "matrix") affine_matrix(v, sm, st);
      else fail(step.begin()->first, "unknown transform step '" + key + "' (scale, rotate, translate or matrix)");
      m = sm * m;
      t = sm * t + st;
    }
    check_determinant(list, m.determinant(), "the transform");
    return Transform::affine(m, t);
  }
  if (const YAML::Node v = n["matrix"]) {
    for (const char* k : {"scale", "rotate", "translate"})
      if (n[k]) fail(n[k], std::string("give either 'matrix' or '") + k + "', not both (or write a transform list)");
    Mat3 m;
    Vec3 t(0);
    affine_matrix(v, m, t);
    return Transform::affine(m, t);
  }
  Transform t;
  if (const auto v = n["scale"]) t.scale = scale(v, what);
  if (const auto v = n["translate"]) t.translate = vec3(v, "translate");
  if (const auto v = n["rotate"]) {
    if (!v.IsMap()) {
      t.rotate_degrees = vec3(v, "rotate");
    } else {  // about an axis: still scale, rotate, translate
      const Mat3 m = rotation(v) * Mat3::scale(t.scale);
      return Transform::affine(m, t.translate);
    }
  }
  return t;
}

Vec3 YamlReader::scale(const YAML::Node& v, const std::string& what) const {
  const Vec3 s = v.IsScalar() ? Vec3(number(v, "scale")) : vec3(v, "scale");
  if (s.x == 0 || s.y == 0 || s.z == 0) fail(v, what + "scale must not be zero");
  return s;
}

// [x, y, z] (degrees about x, then y, then z) or {axis: [x, y, z], angle: degrees}.
Mat3 YamlReader::rotation(const YAML::Node& v) const {
  if (!v.IsMap()) {
    const Vec3 r = vec3(v, "rotate");
    return Mat3::rotation(2, r.z) * Mat3::rotation(1, r.y) * Mat3::rotation(0, r.x);
  }
  keys(v, {"axis", "angle"}, "rotate");
  const YAML::Node a = required(v, "axis", "rotate");
  const Vec3 axis = vec3(a, "rotate axis");
  if (axis == Vec3(0)) fail(a, "rotate axis must not be the zero vector");
  return Mat3::rotation(axis / max_abs_component(axis), number(required(v, "angle", "rotate"), "rotate angle"));
}

// An affine matrix: three rows of four numbers [m, m, m, t] (or of three: no translation), or
// four rows whose last is [0, 0, 0, 1]. Not singular.
void YamlReader::affine_matrix(const YAML::Node& v, Mat3& m, Vec3& t) const {
  const char* shape = "matrix must be a list of 3 or 4 rows of 4 numbers (3 rows of 3: no translation)";
  if (!v.IsSequence() || (v.size() != 3 && v.size() != 4)) fail(v, shape);
  const std::size_t columns = v[0].IsSequence() ? v[0].size() : 0;
  if ((columns != 3 && columns != 4) || (v.size() == 4 && columns != 4)) fail(v, shape);
  Real e[4][4] = {};
  for (std::size_t r = 0; r < v.size(); ++r) {
    if (!v[r].IsSequence() || v[r].size() != columns) fail(v[r], shape);
    for (std::size_t c = 0; c < columns; ++c) e[r][c] = number(v[r][c], "matrix element");
  }
  if (v.size() == 4 && !(e[3][0] == 0 && e[3][1] == 0 && e[3][2] == 0 && e[3][3] == 1))
    fail(v[3], "a 4x4 matrix's last row must be [0, 0, 0, 1] (an affine map; projective ones are not supported)");
  for (int r = 0; r < 3; ++r) m.row[r] = {e[r][0], e[r][1], e[r][2]};
  t = {e[0][3], e[1][3], e[2][3]};
  check_determinant(v, m.determinant(), "matrix");
}

void YamlReader::check_determinant(const YAML::Node& v, Real det, const std::string& what) const {
  if (!std::isfinite(det)) fail(v, what + "'s determinant is not finite (its entries are too large)");
  if (det == 0) fail(v, what + " is singular (its determinant is 0): it flattens the object");
}

}  // namespace strahl
