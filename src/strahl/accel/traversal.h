#pragma once
// The contract between acceleration structures and the queries run through them.
//
// A structure's traverse(view, ray, t_min, t_max, visitor) calls
//     bool visitor(std::uint32_t prim, Real leaf_t_lo, Real leaf_t_hi, Real& t_max)
// for the primitives of every leaf the ray reaches within (t_min, t_max). The visitor may lower
// t_max (a nearer hit was found) and returns true to stop the traversal at once. Structures that
// list a primitive in several leaves (kd-tree, octree) pass the leaf's own parameter interval;
// visitors that count crossings count only those inside it, so nothing is counted twice. The
// others pass (−∞, ∞).

#include "strahl/math/ray.h"

namespace strahl {

STRAHL_HOST_DEVICE inline Vec3 reciprocal(const Vec3& d) { return {Real(1) / d.x, Real(1) / d.y, Real(1) / d.z}; }

}  // namespace strahl
