#pragma once
// Objects placed by a transform (SceneObject::placement): solids keep it (kernel side:
// geometry/placement.h); planes and triangles take it into their coordinates.

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

// A plane's or a triangle's placement taken into its coordinates (by the scene loader for a
// file's keys, by compile() for the C++ API's). A singular map (a scale of 0) is an error at `loc`.
// The plane N·p = d carried by p' = M·p + t: its normal by M's inverse transpose, a point of it
// (N·d/|N|²) by the map; the front side stays in front. N must not be zero.
void place_plane(const Transform& x, Vec3& normal, Real& distance, const FileLoc& loc);
// The vertices carried by the map; a mirroring map swaps two, so that the front face stays in front.
void place_triangle(const Transform& x, Vec3& a, Vec3& b, Vec3& c, const FileLoc& loc);

}  // namespace strahl
