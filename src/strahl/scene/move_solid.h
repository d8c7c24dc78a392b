#pragma once
// A solid's motion (motion blur): the solid just compiled leaves the static ones for
// RenderScene::moving_solids, carried by the motion's map at shutter open and close
// (geometry/moving_solid.h). Spheres (scene/compile.cpp) and meshes have motions of their own.

#include "strahl/camera/camera.h"
#include "strahl/geometry/moving_map.h"
#include "strahl/scene/place_solid.h"
#include "strahl/scene/scene.h"

namespace strahl {

struct RenderScene;

// A motion's values: finite, no scale of 0, no spin about a zero axis (an error at `loc`).
void validate_motion(const Motion& m, const FileLoc& loc);

// The motion's map A(u) over the shutter (geometry/moving_map.h), followed by `post` when given
// (a mesh's transform): at shutter open a keyframe's `from` (or the velocity's displacement at
// that time), at close its `to`, and between them the turn from one to the other taken uniformly
// (the keys' linear parts' orthogonal factors, Q₁·Q₀ᵀ, as an axis and an angle below a half
// turn) with the rest blended — or, with a spin, the spin's turn about its centre (the keys may
// then not turn). Checked: finite, and invertible at every time of the shutter (else an error at
// `loc` naming `what`: keyframes a half turn apart, turning beside a spin, a scale changing sign).
kernel::MovingMap moving_map(const Motion& motion, const Camera& camera, const FileLoc& loc, const char* what,
                             const Affine* post = nullptr);

// Follows the map by `post` (A(u), then x ↦ post.m·x + post.t): its post map and that map's
// inverse; nothing where `post` is the identity (the map's bits stay those without one).
void set_post(kernel::MovingMap& map, const Affine& post);
// The map's post map as set_post() left it (meaningful where map.post is 1).
Affine post_map(const kernel::MovingMap& map);

// A mesh's transform as the post map of its motion (its keys act in its own coordinates, before
// the transform), checked: finite, no scale of 0 (errors at `loc`).
Affine mesh_motion_post(const Transform& transform, const FileLoc& loc);

// Does the motion turn what it moves (keyframes whose rotations differ, a spin)? Such spheres, triangles
// and meshes move as solids or instances do, on arcs (their blends of vertices and centres
// would move on chords). The errors of moving_map().
bool motion_turns(const Motion& motion, const Camera& camera, const FileLoc& loc, const char* what);

// Moves the last solid of out.solids by `motion` (which moves): after the solid's own placement,
// by moving_map's A(u). Errors at `loc`: a solid without bounds (an unclipped quadric, a CSG tree
// around an inverse), a motion whose map flattens the solid at some time of the shutter
// (keyframes a half turn apart, a scale changing sign), positions outside the supported
// coordinates.
void move_last_solid(RenderScene& out, const Motion& motion, const FileLoc& loc);

}  // namespace strahl
