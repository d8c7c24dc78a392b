#pragma once
// Spheres and triangles as plain arrays, seen as a PrimitiveSet (spheres first, then triangles,
// no solids): what the accelerator, packet and portable-kernel tests build their scenes from.

#include <cstdint>
#include <vector>

#include "strahl/accel/primitive.h"

namespace strahl::test {

struct ShapeSoup {
  std::vector<kernel::Sphere> spheres;
  std::vector<kernel::Triangle> triangles;

  PrimitiveSet set() const {
    PrimitiveSet p;
    p.spheres = spheres.data();
    p.sphere_count = std::uint32_t(spheres.size());
    p.triangles = triangles.data();
    p.triangle_count = std::uint32_t(triangles.size());
    return p;
  }
  void sphere(const Vec3& c, Real r) { spheres.push_back({c, r, 0}); }
  void triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
    kernel::Triangle t;
    t.v0 = a;
    t.v1 = b;
    t.v2 = c;
    triangles.push_back(t);
  }
};

}  // namespace strahl::test
