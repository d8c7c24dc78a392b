#pragma once
// A CSG tree as kernel data: a postfix program over its leaves (geometry/csg.h runs it).
// The scene's union, intersection, difference, merge and inverse nodes become binary steps:
// union(A, B, C) is A B Union C Union; difference(A, B) is A Skip(3) B Inverse Intersection.
// Skip(n) before the second operand of an intersection (a difference's too): where the first
// operand's list is empty and starts outside, the next n instructions — the other operand and the
// step — cannot change it (nothing ∩ anything is nothing), so they are not run. POV-Ray stops an
// intersection's children likewise at the first one the ray misses. Where the other operand is a
// single leaf with a box (CsgLeaf) that the ray misses, the step's result is known as well and
// the n instructions are not run either (geometry/csg.h, csg_evaluate).

#include <cstdint>

#include "strahl/math/vec3.h"

namespace strahl::kernel {

enum class CsgOp : std::uint8_t { Leaf, Inverse, Union, Intersection, Merge, Skip };

struct CsgInstruction {
  CsgOp op = CsgOp::Leaf;
  std::uint8_t pad = 0;
  std::uint16_t arg = 0;  // Leaf: which of the tree's leaves; Skip: how many instructions
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
