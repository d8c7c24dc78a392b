#pragma once
// A CSG tree as kernel data: a postfix program over its leaves (geometry/csg.h runs it).
// The scene's union, intersection, difference, merge and inverse nodes become binary steps:
// union(A, B, C) is A B Union C Union; difference(A, B) is A Skip(3) B Inverse Intersection.
//
// Skip(n) stands before steps of one node — one step (its other operand and the operation), or a
// group of consecutive steps — and may leave the next n instructions out where their result is
// known without them:
//   * before an intersection's or a difference's steps, where the list so far is empty and starts
//     outside (nothing ∩ anything is nothing; POV-Ray stops an intersection's children likewise
//     at the first one the ray misses);
//   * where it names a box (`box`, an entry of the tree's CsgLeaf array: a leaf's own, or one
//     after the leaves) that the ray's range misses: the box holds every operand of the n
//     instructions (leaves with boxes, and nodes of them without an inverse), so each of them has
//     no crossing there and is outside. An intersection with such operands is empty; a difference
//     with them, a union or merge with them, is the list so far itself where that is simple
//     (csg_simple).
// A node with many small operands (a plate with a grid of holes) gets nested groups: a Skip over
// all its steps, Skips over halves of them within, and so on down to the steps' own, so a ray
// tests O(log n) boxes for the operands it does not meet instead of one box per operand.

#include <cstdint>

#include "strahl/math/vec3.h"

namespace strahl::kernel {

enum class CsgOp : std::uint8_t { Leaf, Inverse, Union, Intersection, Merge, Skip };

// Which steps a Skip stands before (what their operands missing the ray's range leaves).
enum class CsgRun : std::uint8_t { Intersection, Difference, Union };  // Union: union or merge steps

inline constexpr std::uint32_t kNoCsgBox = 0xffffffffu;

struct CsgInstruction {
  CsgOp op = CsgOp::Leaf;
  CsgRun run = CsgRun::Intersection;  // Skip: the node's steps
  std::uint16_t arg = 0;              // Leaf: which of the tree's leaves; Skip: how many instructions
  std::uint32_t box = kNoCsgBox;      // Skip: the tree's CsgLeaf entry whose box holds the operands
};

// Limits (docs/scene-format.md, "CSG"): the program's evaluation stack (one crossing list per
// entry) and the leaves one tree may have (a leaf's index is kept in 16 bits of a crossing's part).
inline constexpr int kMaxCsgStack = 8;
inline constexpr int kMaxCsgLeaves = 256;

struct Csg {
  std::uint32_t first_instruction = 0, instruction_count = 0;
  std::uint32_t first_leaf = 0, leaf_count = 0;
  Vec3 lo, hi;  // bounds (infinite for an unbounded tree)
};

}  // namespace strahl::kernel
