#pragma once
// Solids placed by a transform (SceneObject::placement; kernel side: geometry/placement.h).

#include "strahl/math/transform.h"
#include "strahl/util/error.h"

namespace strahl {

struct RenderScene;

// p_world = m · p_object + t.
struct Affine {
  Mat3 m;
  Vec3 t{0};
};

inline Affine affine_of(const Transform& x) { return {x.linear(), x.translate}; }
// `outer` after `inner`.
inline Affine compose(const Affine& outer, const Affine& inner) { return {outer.m * inner.m, outer.m * inner.t + outer.t}; }

// Places the last solid of out.solids by `to_world` (after the placement it may have already):
// it becomes a kernel::PlacedSolid with world bounds. A singular transform (a scale of 0) is an
// error at `loc`.
void place_last_solid(RenderScene& out, const Affine& to_world, const FileLoc& loc);

}  // namespace strahl
