#pragma once
// The nearest intersection found so far along a ray: which primitive, at which t.
// Surface details (point, normal, material) are derived only for the final nearest hit.

#include <cstdint>

#include "strahl/math/config.h"

namespace strahl {

enum class ShapeKind : std::uint8_t {
  None, Sphere, Plane, Triangle, MovingSphere, MovingTriangle, Solid, Instance, MovingSolid, MovingInstance
};

struct Hit {
  Real t = kInfinity;
  ShapeKind kind = ShapeKind::None;
  std::uint32_t index = 0;  // into the RenderScene's array for `kind`
  std::uint32_t prim = 0;   // Instance: the primitive in its group's structure (index: the instance)
  Real b1 = 0, b2 = 0;      // barycentric coordinates of triangle hits; a solid's part in b1

  STRAHL_HOST_DEVICE constexpr bool found() const { return kind != ShapeKind::None; }
};

}  // namespace strahl
