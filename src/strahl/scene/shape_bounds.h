#pragma once
// Boxes around sets of shapes, for the compile step (instances' group boxes, the scene box the
// warnings look at).

#include "strahl/accel/primitive.h"
#include "strahl/math/bounds.h"

namespace strahl {

inline void extend(Bounds& b, const Bounds& other) {
  b.extend(other.lo);
  b.extend(other.hi);
}

// The box around every primitive of the set (empty when it has none).
inline Bounds bounds_of(const PrimitiveSet& prims) {
  Bounds b;
  for (std::uint32_t p = 0; p < prims.size(); ++p) extend(b, primitive_bounds(prims, p));
  return b;
}

}  // namespace strahl
