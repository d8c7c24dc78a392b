#pragma once
// Splitting one mesh polygon (an OBJ face with more than three corners) into triangles, in time
// linear in its corners for convex polygons (docs/scene-format.md, "What is read from the OBJ
// file"):
//   * a convex polygon is split into a fan around its first corner (a quad along its shorter
//     diagonal, as tinyobjloader did);
//   * any other polygon by ear clipping in its plane, testing candidate ears only against the
//     reflex corners: about n·r steps for n corners of which r are reflex.
// "Convex" allows dents below the precision of the file's numbers (a 200,000-corner circle
// written with seven digits has corners that turn the wrong way by rounding alone).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "strahl/math/vec3.h"

namespace strahl {

using PolygonTriangle = std::array<std::uint32_t, 3>;  // corner numbers 0 … n−1

// Appends the n − 2 triangles of the polygon with corners `corners` (in order, n ≥ 3) to
// `triangles`. Returns false, appending nothing, when ear clipping would take more than
// `max_steps` point-in-triangle tests (a huge polygon with very many reflex corners).
bool triangulate_polygon(std::span<const Vec3> corners, std::vector<PolygonTriangle>& triangles,
                         std::uint64_t max_steps = 50'000'000);

}  // namespace strahl
