#pragma once
// A compiled function f(x, y, z) for implicit surfaces (lecture 2.1: "finde Menge aller Punkte
// mit f(x, y, z) = 0"): a fixed-size postfix program that kernel code runs on a small stack.
// The program is written by the expression compiler (scene/expression_compiler.h), which checks
// both bounds below, so evaluate() trusts it: no allocation, no virtual calls, no checks per op.
//
// Semantics, identical in constant folding (the compiler calls the same apply functions) and in
// evaluation: IEEE double with the C library's functions — sin cos tan asin acos atan exp log
// sqrt fabs floor, atan2(y, x), pow, fmod (mod); min(a, b) = b < a ? b : a and max(a, b) =
// b > a ? b : a, except that a NaN argument is ignored (as fmin/fmax do, but with the first
// argument kept for equal values, so −0 and +0 do not depend on the C library);
// clamp(v, lo, hi) = min(max(v, lo), hi). A whole-number constant exponent 2 or 3 multiplies
// (x·x, (x·x)·x): exact, and far cheaper than pow.

#include <cmath>
#include <cstdint>

#include "strahl/math/vec3.h"

namespace strahl::kernel {

// Longest program (instructions after constant folding) and deepest stack an expression may
// need; the compiler refuses larger ones. 256 instructions hold e.g. a sum of 60 terms a·sin(b·x).
inline constexpr int kMaxExpressionLength = 256;
inline constexpr int kMaxExpressionStack = 32;
inline constexpr int kMaxExpressionConstants = 64;

enum class Op : std::uint8_t {
  // push
  X, Y, Z, Const,
  // unary: replace the top
  Neg, Sin, Cos, Tan, Asin, Acos, Atan, Exp, Log, Sqrt, Abs, Floor, Square, Cube,
  // binary: pop b, replace a by a ∘ b
  Add, Sub, Mul, Div, Pow, Atan2, Min, Max, Mod,
  // ternary: clamp(v, lo, hi)
  Clamp,
};

inline constexpr int kOpCount = int(Op::Clamp) + 1;

STRAHL_HOST_DEVICE constexpr int op_arity(Op op) {
  return op <= Op::Const ? 0 : op <= Op::Cube ? 1 : op <= Op::Mod ? 2 : 3;
}

struct Instruction {
  Op op = Op::Const;
  std::uint8_t arg = 0;  // Const: index into Expression::constants
};

struct Expression {
  std::uint16_t length = 0;      // instructions used
  std::uint8_t stack_depth = 0;  // the deepest the stack gets (for tests; evaluate() needs no check)
  std::uint8_t constant_count = 0;
  Instruction code[kMaxExpressionLength];
  Real constants[kMaxExpressionConstants] = {};
};

STRAHL_HOST_DEVICE inline Real apply_unary(Op op, Real a) {
  switch (op) {
    case Op::Neg: return -a;
    case Op::Sin: return std::sin(a);
    case Op::Cos: return std::cos(a);
    case Op::Tan: return std::tan(a);
    case Op::Asin: return std::asin(a);
    case Op::Acos: return std::acos(a);
    case Op::Atan: return std::atan(a);
    case Op::Exp: return std::exp(a);
    case Op::Log: return std::log(a);
    case Op::Sqrt: return std::sqrt(a);
    case Op::Abs: return std::fabs(a);
    case Op::Floor: return std::floor(a);
    case Op::Square: return a * a;
    case Op::Cube: return a * a * a;
    default: return a;
  }
}

STRAHL_HOST_DEVICE inline Real expression_min(Real a, Real b) { return a != a ? b : b < a ? b : a; }
STRAHL_HOST_DEVICE inline Real expression_max(Real a, Real b) { return a != a ? b : b > a ? b : a; }

STRAHL_HOST_DEVICE inline Real apply_binary(Op op, Real a, Real b) {
  switch (op) {
    case Op::Add: return a + b;
    case Op::Sub: return a - b;
    case Op::Mul: return a * b;
    case Op::Div: return a / b;
    case Op::Pow: return std::pow(a, b);
    case Op::Atan2: return std::atan2(a, b);
    case Op::Min: return expression_min(a, b);
    case Op::Max: return expression_max(a, b);
    case Op::Mod: return std::fmod(a, b);
    default: return a;
  }
}

STRAHL_HOST_DEVICE inline Real apply_clamp(Real v, Real lo, Real hi) { return expression_min(expression_max(v, lo), hi); }

// f(p). The stack pointer `top` indexes the topmost value.
STRAHL_HOST_DEVICE inline Real evaluate(const Expression& e, const Vec3& p) {
  Real stack[kMaxExpressionStack];
  int top = -1;
  for (int i = 0; i < e.length; ++i) {
    const Instruction in = e.code[i];
    switch (in.op) {
      case Op::X: stack[++top] = p.x; break;
      case Op::Y: stack[++top] = p.y; break;
      case Op::Z: stack[++top] = p.z; break;
      case Op::Const: stack[++top] = e.constants[in.arg]; break;
      case Op::Add: --top; stack[top] = stack[top] + stack[top + 1]; break;
      case Op::Sub: --top; stack[top] = stack[top] - stack[top + 1]; break;
      case Op::Mul: --top; stack[top] = stack[top] * stack[top + 1]; break;
      case Op::Square: stack[top] = stack[top] * stack[top]; break;
      case Op::Clamp: top -= 2; stack[top] = apply_clamp(stack[top], stack[top + 1], stack[top + 2]); break;
      default:
        if (op_arity(in.op) == 1) {
          stack[top] = apply_unary(in.op, stack[top]);
        } else {
          --top;
          stack[top] = apply_binary(in.op, stack[top], stack[top + 1]);
        }
        break;
    }
  }
  return stack[0];
}

}  // namespace strahl::kernel
