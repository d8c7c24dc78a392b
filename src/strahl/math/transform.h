#pragma once
// Affine transforms for placing objects: p' = M·p + t, normals by the inverse transpose of M.

#include <cmath>
#include <memory>

#include "strahl/math/vec3.h"

namespace strahl {

struct Mat3 {
  Vec3 row[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  Vec3 operator*(const Vec3& v) const { return {dot(row[0], v), dot(row[1], v), dot(row[2], v)}; }
  Mat3 operator*(const Mat3& o) const {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      r.row[i] = Vec3(dot(row[i], Vec3(o.row[0].x, o.row[1].x, o.row[2].x)),
                      dot(row[i], Vec3(o.row[0].y, o.row[1].y, o.row[2].y)),
                      dot(row[i], Vec3(o.row[0].z, o.row[1].z, o.row[2].z)));
    return r;
  }
  Mat3 transposed() const {
    Mat3 r;
    r.row[0] = {row[0].x, row[1].x, row[2].x};
    r.row[1] = {row[0].y, row[1].y, row[2].y};
    r.row[2] = {row[0].z, row[1].z, row[2].z};
    return r;
  }
  Real determinant() const { return dot(row[0], cross(row[1], row[2])); }
  // Inverse by cofactors; the caller checks the determinant is not zero.
  Mat3 inverse() const {
    const Real inv_det = Real(1) / determinant();
    Mat3 cof;
    cof.row[0] = cross(row[1], row[2]);
    cof.row[1] = cross(row[2], row[0]);
    cof.row[2] = cross(row[0], row[1]);
    Mat3 r = cof.transposed();
    for (Vec3& v : r.row) v *= inv_det;
    return r;
  }
  static Mat3 scale(const Vec3& s) {
    Mat3 m;
    m.row[0] = {s.x, 0, 0}; m.row[1] = {0, s.y, 0}; m.row[2] = {0, 0, s.z};
    return m;
  }
  // Rotation about a coordinate axis (0 = x, 1 = y, 2 = z) by `degrees`, right-handed.
  static Mat3 rotation(int axis, Real degrees) {
    const Real a = degrees * kPi / 180, c = std::cos(a), s = std::sin(a);
    Mat3 m;
    if (axis == 0) { m.row[1] = {0, c, -s}; m.row[2] = {0, s, c}; }
    if (axis == 1) { m.row[0] = {c, 0, s}; m.row[2] = {-s, 0, c}; }
    if (axis == 2) { m.row[0] = {c, -s, 0}; m.row[1] = {s, c, 0}; }
    return m;
  }
  // Rotation by `degrees` about `axis` (not zero; need not be unit length), right-handed
  // (Rodrigues' formula).
  static Mat3 rotation(const Vec3& axis, Real degrees) {
    const Vec3 u = axis / std::sqrt(dot(axis, axis));
    const Real a = degrees * kPi / 180, c = std::cos(a), s = std::sin(a), k = 1 - c;
    Mat3 m;
    m.row[0] = {c + u.x * u.x * k, u.x * u.y * k - u.z * s, u.x * u.z * k + u.y * s};
    m.row[1] = {u.y * u.x * k + u.z * s, c + u.y * u.y * k, u.y * u.z * k - u.x * s};
    m.row[2] = {u.z * u.x * k - u.y * s, u.z * u.y * k + u.x * s, c + u.z * u.z * k};
    return m;
  }
};

// Either the fixed-order keys (scale, then rotate about x, y, z, then translate) or, when
// general() (a `matrix`, an axis-and-angle rotation or a `transform` list, composed by the scene
// loader), any affine map p' = matrix()·p + translate, scale and rotate_degrees unused. The
// general matrix is held by a pointer, so that the many objects without one stay small.
struct Transform {
  Vec3 scale{1};
  Vec3 rotate_degrees{0};  // applied about x, then y, then z
  Vec3 translate{0};
  std::shared_ptr<const Mat3> general_matrix;

  static Transform affine(const Mat3& m, const Vec3& t) {
    Transform x;
    x.general_matrix = std::make_shared<const Mat3>(m);
    x.translate = t;
    return x;
  }
  bool general() const { return general_matrix != nullptr; }
  const Mat3& matrix() const { return *general_matrix; }
  bool identity() const {
    if (general()) {
      const Mat3 i;
      const Mat3& m = *general_matrix;
      return m.row[0] == i.row[0] && m.row[1] == i.row[1] && m.row[2] == i.row[2] && translate == Vec3(0);
    }
    return scale == Vec3(1) && rotate_degrees == Vec3(0) && translate == Vec3(0);
  }

  Mat3 linear() const {
    if (general()) return *general_matrix;
    return Mat3::rotation(2, rotate_degrees.z) * Mat3::rotation(1, rotate_degrees.y) *
           Mat3::rotation(0, rotate_degrees.x) * Mat3::scale(scale);
  }
};

}  // namespace strahl
