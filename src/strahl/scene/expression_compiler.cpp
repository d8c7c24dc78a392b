// Parse tree → postfix program (and its fused form, kernel::fuse()): constant folding, x^2 / x^3
// as multiplications, operand order chosen for a shallow stack, and the bounds of
// geometry/expression.h enforced.

#include "strahl/scene/expression_compiler.h"

#include <algorithm>
#include <cstring>

#include "strahl/scene/expression_ast.h"

namespace strahl {
namespace {

using kernel::Op;
using expression::Node;
using expression::Tree;

class Compiler {
 public:
  explicit Compiler(Tree& tree) : tree_(tree) {}

  kernel::Expression run() {
    fold(tree_.root);
    const int depth = need(tree_.root);
    if (depth > kernel::kMaxExpressionStack)
      fail("the expression nests too deeply: it needs a stack of " + std::to_string(depth) + " values (at most " +
           std::to_string(kernel::kMaxExpressionStack) + ")");
    emit(tree_.root);
    out_.stack_depth = std::uint8_t(depth);
    kernel::fuse(out_);
    return out_;
  }

 private:
  [[noreturn]] static void fail(const std::string& message) { throw ExpressionError(1, message); }

  Node& node(int i) { return tree_.nodes[std::size_t(i)]; }

  // Children first; a node whose operands are all constants becomes one, computed by the
  // kernel's own functions so that folding changes no bit of the result.
  void fold(int i) {
    Node& n = node(i);
    const int arity = kernel::op_arity(n.op);
    bool constant = true;
    for (int k = 0; k < arity; ++k) {
      fold(n.child[k]);
      constant = constant && node(n.child[k]).op == Op::Const;
    }
    if (n.op == Op::Pow && node(n.child[1]).op == Op::Const) {
      const Real e = node(n.child[1]).value;
      if (e == 2 || e == 3) {
        n.op = e == 2 ? Op::Square : Op::Cube;
        n.child[1] = -1;
        fold(i);
        return;
      }
    }
    if (arity == 0 || !constant) return;
    const Real a = node(n.child[0]).value;
    if (arity == 1) n.value = kernel::apply_unary(n.op, a);
    if (arity == 2) n.value = kernel::apply_binary(n.op, a, node(n.child[1]).value);
    if (arity == 3) n.value = kernel::apply_clamp(a, node(n.child[1]).value, node(n.child[2]).value);
    n.op = Op::Const;
    n.child[0] = n.child[1] = n.child[2] = -1;
  }

  static bool commutative(Op op) { return op == Op::Add || op == Op::Mul; }

  // Stack values needed to evaluate node i (Sethi–Ullman): operand k is evaluated with k values
  // already on the stack. Commutative operands go deeper-first.
  int need(int i) {
    Node& n = node(i);
    const int arity = kernel::op_arity(n.op);
    if (arity == 0) return 1;
    int d[3] = {0, 0, 0};
    for (int k = 0; k < arity; ++k) d[k] = need(n.child[k]);
    if (commutative(n.op) && d[1] > d[0]) {
      std::swap(n.child[0], n.child[1]);
      std::swap(d[0], d[1]);
    }
    int depth = 0;
    for (int k = 0; k < arity; ++k) depth = std::max(depth, d[k] + k);
    return depth;
  }

  void emit(int i) {
    const Node& n = node(i);
    const int arity = kernel::op_arity(n.op);
    for (int k = 0; k < arity; ++k) emit(n.child[k]);
    kernel::Instruction in;
    in.op = n.op;
    if (n.op == Op::Const) in.arg = constant(n.value);
    if (out_.length >= kernel::kMaxExpressionLength)
      fail("the expression is too long: more than " + std::to_string(kernel::kMaxExpressionLength) +
           " operations after folding constants");
    out_.code[out_.length++] = in;
  }

  // Index of a constant in the pool, shared by equal bit patterns.
  std::uint8_t constant(Real v) {
    for (int k = 0; k < out_.constant_count; ++k)
      if (std::memcmp(&out_.constants[k], &v, sizeof v) == 0) return std::uint8_t(k);
    if (out_.constant_count >= kernel::kMaxExpressionConstants)
      fail("the expression has too many different constants (at most " +
           std::to_string(kernel::kMaxExpressionConstants) + ")");
    out_.constants[out_.constant_count] = v;
    return out_.constant_count++;
  }

  Tree& tree_;
  kernel::Expression out_;
};

}  // namespace

kernel::Expression compile_expression(std::string_view text, const ExpressionParameters& parameters) {
  Tree tree = expression::parse(text, parameters);
  return Compiler(tree).run();
}

bool uses_coordinates(const kernel::Expression& e) {
  for (int i = 0; i < e.length; ++i)
    if (e.code[i].op == Op::X || e.code[i].op == Op::Y || e.code[i].op == Op::Z) return true;
  return false;
}

}  // namespace strahl
