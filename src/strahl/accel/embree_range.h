#pragma once
// The scenes Embree can hold. Embree traverses and intersects triangles in float: its products
// of coordinates under- and overflow far inside strahl's own range (docs/scene-format.md, "Units
// and scale"), it cannot resolve a primitive much smaller than float's spacing at its position,
// and it refuses rays from beyond ~1.8e18 (FLT_LARGE). For a scene outside these limits,
// build_accel(AccelKind::Embree, …) builds the BVH instead (compile() says so in a warning), and
// an Embree query whose ray starts beyond kEmbreeMaxCoordinate is answered by the naive loop.

#include <string>

#include "strahl/accel/primitive.h"

namespace strahl {

inline constexpr Real kEmbreeMaxCoordinate = Real(1e15);
inline constexpr Real kEmbreeMinSize = Real(1e-10);          // a primitive's extent, absolute
inline constexpr Real kEmbreeMinRelativeSize = Real(1e-5);   // … and relative to its position (~170 float ulps)

// Why Embree cannot hold these primitives ("a primitive of size 2e-12 at 0.31 …"), or "".
std::string embree_misfit(const PrimitiveSet& prims);

}  // namespace strahl
