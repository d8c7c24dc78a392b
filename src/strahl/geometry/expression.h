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
//
// evaluate() runs a second form of the same program, derived from it by fuse(): the top of the
// stack lives in a register, and a binary operation whose right operand is x, y, z or a constant
// reads it directly instead of pushing it (`x 0.15 Sub` becomes `x Sub·c0.15`). The same IEEE
// operations on the same operands in the same order: the values are identical to the postfix
// program's bit for bit (evaluate_postfix(), kept as the reference), in about half the time.
// A squared term added to the register adds it without a push (`… x a Sub Square Add` becomes
// `… AddSquaredXMinus·a`: register + (x − a)², the same addition of the same operands), and
// sqrt, sin and cos have operations of their own instead of Unary's second dispatch: a distance
// sqrt((x − a)² + (y − b)² + (z − c)²) is four operations instead of six.

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

// The fused program's operations (see above). Push*: the register goes onto the stack and takes
// the leaf; Unary: the register's function (arg: the Op); Binary: the popped value ∘ the register
// (arg: the Op); the rest: the register ∘ the leaf named, for the four arithmetic operations.
enum class FusedOp : std::uint8_t {
  PushX, PushY, PushZ, PushConst,
  Unary, Square, Binary, Add, Sub, Mul, Clamp,
  AddX, AddY, AddZ, AddConst,
  SubX, SubY, SubZ, SubConst,
  MulX, MulY, MulZ, MulConst,
  DivX, DivY, DivZ, DivConst,
  // push (leaf ∓ constant)²: the terms of a distance, (x − a)² (`x a Sub Square`)
  PushSquaredXMinus, PushSquaredYMinus, PushSquaredZMinus,
  PushSquaredXPlus, PushSquaredYPlus, PushSquaredZPlus,
  // the register + (leaf ∓ constant)²: such a term followed by Add
  AddSquaredXMinus, AddSquaredYMinus, AddSquaredZMinus,
  AddSquaredXPlus, AddSquaredYPlus, AddSquaredZPlus,
  // the register's function without Unary's dispatch
  Sqrt, Sin, Cos,
};

struct FusedInstruction {
  FusedOp op = FusedOp::PushConst;
  std::uint8_t arg = 0;  // *Const: index into Expression::constants; Unary, Binary: the Op
};

struct Expression {
  std::uint16_t length = 0;      // instructions used
  std::uint8_t stack_depth = 0;  // the deepest the stack gets (for tests; evaluate() needs no check)
  std::uint8_t constant_count = 0;
  std::uint16_t fused_length = 0;  // 0: fuse() has not run, evaluate() runs `code`
  Instruction code[kMaxExpressionLength];
  FusedInstruction fused[kMaxExpressionLength];  // fuse(code): never longer
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

// f(p) by the postfix program. The stack pointer `top` indexes the topmost value.
STRAHL_HOST_DEVICE inline Real evaluate_postfix(const Expression& e, const Vec3& p) {
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

// Writes e.fused from e.code (the compiler calls it once; host or device).
STRAHL_HOST_DEVICE inline void fuse(Expression& e) {
  int n = 0;
  for (int i = 0; i < e.length; ++i) {
    const Instruction in = e.code[i];
    FusedInstruction out;
    const bool leaf = op_arity(in.op) == 0;
    const Op next = i + 1 < e.length ? e.code[i + 1].op : Op::Const;
    const bool coordinate = in.op == Op::X || in.op == Op::Y || in.op == Op::Z;
    if (coordinate && i + 3 < e.length && e.code[i + 1].op == Op::Const &&
        (e.code[i + 2].op == Op::Sub || e.code[i + 2].op == Op::Add) && e.code[i + 3].op == Op::Square) {
      const bool minus = e.code[i + 2].op == Op::Sub;
      // Followed by Add (and not the program's first value, which has nothing to add to): the
      // register + the square, without the push.
      const bool add = n > 0 && i + 4 < e.length && e.code[i + 4].op == Op::Add;
      const FusedOp first = add ? (minus ? FusedOp::AddSquaredXMinus : FusedOp::AddSquaredXPlus)
                                : (minus ? FusedOp::PushSquaredXMinus : FusedOp::PushSquaredXPlus);
      out.op = FusedOp(int(first) + int(in.op));
      out.arg = e.code[i + 1].arg;
      i += add ? 4 : 3;
    } else if (leaf && (next == Op::Add || next == Op::Sub || next == Op::Mul || next == Op::Div)) {
      // register ∘ leaf: Add, Sub, Mul, Div are four consecutive groups of X, Y, Z, Const.
      const int group = next == Op::Add ? 0 : next == Op::Sub ? 1 : next == Op::Mul ? 2 : 3;
      out.op = FusedOp(int(FusedOp::AddX) + 4 * group + int(in.op));  // Op::X..Const are 0..3
      out.arg = in.arg;
      ++i;  // the operation is consumed
    } else if (leaf) {
      out.op = FusedOp(int(FusedOp::PushX) + int(in.op));
      out.arg = in.arg;
    } else if (in.op == Op::Square) {
      out.op = FusedOp::Square;
    } else if (in.op == Op::Add || in.op == Op::Sub || in.op == Op::Mul) {
      out.op = in.op == Op::Add ? FusedOp::Add : in.op == Op::Sub ? FusedOp::Sub : FusedOp::Mul;
    } else if (in.op == Op::Clamp) {
      out.op = FusedOp::Clamp;
    } else if (in.op == Op::Sqrt || in.op == Op::Sin || in.op == Op::Cos) {
      out.op = in.op == Op::Sqrt ? FusedOp::Sqrt : in.op == Op::Sin ? FusedOp::Sin : FusedOp::Cos;
    } else {
      out.op = op_arity(in.op) == 1 ? FusedOp::Unary : FusedOp::Binary;
      out.arg = std::uint8_t(in.op);
    }
    e.fused[n++] = out;
  }
  e.fused_length = std::uint16_t(n);
}

// f(p), by the fused program (the postfix one where fuse() has not run). The register `v` is the
// top of the stack; stack[top] the value below it (stack[0] holds the register's initial 0).
STRAHL_HOST_DEVICE STRAHL_DEVICE_NOINLINE Real evaluate(const Expression& e, const Vec3& p) {
  if (e.fused_length == 0) return evaluate_postfix(e, p);
  Real stack[kMaxExpressionStack];
  int top = -1;
  Real v = 0;
  for (int i = 0; i < e.fused_length; ++i) {
    const FusedInstruction in = e.fused[i];
    switch (in.op) {
      case FusedOp::PushX: stack[++top] = v; v = p.x; break;
      case FusedOp::PushY: stack[++top] = v; v = p.y; break;
      case FusedOp::PushZ: stack[++top] = v; v = p.z; break;
      case FusedOp::PushConst: stack[++top] = v; v = e.constants[in.arg]; break;
      case FusedOp::Unary: v = apply_unary(Op(in.arg), v); break;
      case FusedOp::Square: v = v * v; break;
      case FusedOp::Binary: v = apply_binary(Op(in.arg), stack[top--], v); break;
      case FusedOp::Add: v = stack[top--] + v; break;
      case FusedOp::Sub: v = stack[top--] - v; break;
      case FusedOp::Mul: v = stack[top--] * v; break;
      case FusedOp::Clamp: v = apply_clamp(stack[top - 1], stack[top], v); top -= 2; break;
      case FusedOp::AddX: v = v + p.x; break;
      case FusedOp::AddY: v = v + p.y; break;
      case FusedOp::AddZ: v = v + p.z; break;
      case FusedOp::AddConst: v = v + e.constants[in.arg]; break;
      case FusedOp::SubX: v = v - p.x; break;
      case FusedOp::SubY: v = v - p.y; break;
      case FusedOp::SubZ: v = v - p.z; break;
      case FusedOp::SubConst: v = v - e.constants[in.arg]; break;
      case FusedOp::MulX: v = v * p.x; break;
      case FusedOp::MulY: v = v * p.y; break;
      case FusedOp::MulZ: v = v * p.z; break;
      case FusedOp::MulConst: v = v * e.constants[in.arg]; break;
      case FusedOp::DivX: v = v / p.x; break;
      case FusedOp::DivY: v = v / p.y; break;
      case FusedOp::DivZ: v = v / p.z; break;
      case FusedOp::DivConst: v = v / e.constants[in.arg]; break;
      case FusedOp::PushSquaredXMinus: stack[++top] = v; v = p.x - e.constants[in.arg]; v = v * v; break;
      case FusedOp::PushSquaredYMinus: stack[++top] = v; v = p.y - e.constants[in.arg]; v = v * v; break;
      case FusedOp::PushSquaredZMinus: stack[++top] = v; v = p.z - e.constants[in.arg]; v = v * v; break;
      case FusedOp::PushSquaredXPlus: stack[++top] = v; v = p.x + e.constants[in.arg]; v = v * v; break;
      case FusedOp::PushSquaredYPlus: stack[++top] = v; v = p.y + e.constants[in.arg]; v = v * v; break;
      case FusedOp::PushSquaredZPlus: stack[++top] = v; v = p.z + e.constants[in.arg]; v = v * v; break;
      case FusedOp::AddSquaredXMinus: { const Real d = p.x - e.constants[in.arg]; v = v + d * d; break; }
      case FusedOp::AddSquaredYMinus: { const Real d = p.y - e.constants[in.arg]; v = v + d * d; break; }
      case FusedOp::AddSquaredZMinus: { const Real d = p.z - e.constants[in.arg]; v = v + d * d; break; }
      case FusedOp::AddSquaredXPlus: { const Real d = p.x + e.constants[in.arg]; v = v + d * d; break; }
      case FusedOp::AddSquaredYPlus: { const Real d = p.y + e.constants[in.arg]; v = v + d * d; break; }
      case FusedOp::AddSquaredZPlus: { const Real d = p.z + e.constants[in.arg]; v = v + d * d; break; }
      case FusedOp::Sqrt: v = std::sqrt(v); break;
      case FusedOp::Sin: v = std::sin(v); break;
      case FusedOp::Cos: v = std::cos(v); break;
    }
  }
  return v;
}

}  // namespace strahl::kernel
