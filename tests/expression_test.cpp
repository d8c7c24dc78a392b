// The expression language of implicit surfaces: random expression trees printed as text, compiled
// and evaluated, against a direct C++ evaluation of the same tree; precedence; every error class
// with its column; the documented bounds.
//
// Agreement is demanded bit for bit (NaN matching NaN). The compiled program performs the same
// IEEE operations on the same operands with the same C library functions as the direct
// evaluation: constant folding calls those functions too, and the only reorderings (a+b → b+a,
// a·b → b·a) are exact. A tolerance would only hide differences that have a cause.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "strahl/scene/expression_compiler.h"
#include "test_random.h"

namespace strahl::expression_test {
namespace {

using kernel::Expression;

// ---- random trees, their text and their direct evaluation ----

enum class K { X, Y, Z, Const, Pi, ParamA, ParamB, Neg, Plus, Add, Sub, Mul, Div, Pow, Call };

struct Tree {
  K kind = K::Const;
  Real value = 0;
  std::string fn;  // Call: the function's name
  std::vector<std::unique_ptr<Tree>> args;
};

constexpr Real kA = 0.75, kB = -2.5;

const char* const kUnary[] = {"sin", "cos", "tan", "asin", "acos", "atan", "exp", "log", "sqrt", "abs", "floor"};
const char* const kBinary[] = {"atan2", "pow", "mod", "min", "max"};

class Generator {
 public:
  explicit Generator(std::uint64_t seed) : rng_(seed) {}

  std::unique_ptr<Tree> make(int depth) {
    auto t = std::make_unique<Tree>();
    if (depth == 0 || rng_.below(5) == 0) {
      const int r = rng_.below(10);
      t->kind = r < 4 ? K(r % 3) : r < 8 ? K::Const : r == 8 ? K::Pi : (rng_.coin() ? K::ParamA : K::ParamB);
      if (t->kind == K::Const) t->value = constant();
      return t;
    }
    const int r = rng_.below(12);
    if (r < 6) {
      t->kind = K(int(K::Add) + r % 5);
      t->args.push_back(make(depth - 1));
      // Constant exponents 2 and 3 (the multiplying forms) and negative ones, often.
      if (t->kind == K::Pow && rng_.coin()) {
        auto e = std::make_unique<Tree>();
        e->value = Real(rng_.below(7) - 2);
        t->args.push_back(std::move(e));
      } else {
        t->args.push_back(make(depth - 1));
      }
    } else if (r < 7) {
      t->kind = rng_.coin() ? K::Neg : K::Plus;
      t->args.push_back(make(depth - 1));
    } else {
      t->kind = K::Call;
      const int f = rng_.below(17);
      const int n = f < 11 ? 1 : f < 16 ? 2 : 3;
      t->fn = f < 11 ? kUnary[f] : f < 16 ? kBinary[f - 11] : "clamp";
      const int count = (t->fn == "min" || t->fn == "max") ? 2 + rng_.below(3) : n;
      for (int k = 0; k < count; ++k) t->args.push_back(make(depth - 1));
    }
    return t;
  }

 private:
  Real constant() {
    switch (rng_.below(4)) {
      case 0: return Real(rng_.below(5));          // small whole numbers: 2 and 3 as exponents
      case 1: return rng_.uniform(-4, 4);
      case 2: return rng_.log_uniform(1e-6, 1e6);
      default: return -rng_.uniform(0, 10);        // negative: printed as unary minus
    }
  }
  test::Random rng_;
};

// Precedence levels of the grammar: sum 1, product 2, unary 3, power 4, primary 5.
int level(const Tree& t) {
  switch (t.kind) {
    case K::Add: case K::Sub: return 1;
    case K::Mul: case K::Div: return 2;
    case K::Neg: case K::Plus: return 3;
    case K::Pow: return 4;
    case K::Const: return std::signbit(t.value) ? 3 : 5;
    default: return 5;
  }
}

class Printer {
 public:
  explicit Printer(std::uint64_t seed) : rng_(seed) {}

  std::string print(const Tree& t, int min_level) {
    std::string s = bare(t);
    if (level(t) < min_level || rng_.below(12) == 0) return "(" + space() + s + space() + ")";
    return s;
  }

 private:
  std::string space() { return rng_.below(3) == 0 ? " " : ""; }

  std::string bare(const Tree& t) {
    switch (t.kind) {
      case K::X: return "x";
      case K::Y: return "y";
      case K::Z: return "z";
      case K::Pi: return "pi";
      case K::ParamA: return "a";
      case K::ParamB: return "b";
      case K::Const: {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", std::fabs(t.value));
        return std::signbit(t.value) ? "-" + std::string(buf) : std::string(buf);
      }
      case K::Neg: return "-" + space() + print(*t.args[0], 3);
      case K::Plus: return "+" + space() + print(*t.args[0], 3);
      case K::Add: return binary(t, "+", 1, 2);
      case K::Sub: return binary(t, "-", 1, 2);
      case K::Mul: return binary(t, "*", 2, 3);
      case K::Div: return binary(t, "/", 2, 3);
      case K::Pow: return binary(t, "^", 5, 3);
      case K::Call: {
        std::string s = t.fn + "(";
        for (std::size_t k = 0; k < t.args.size(); ++k) s += (k ? "," + space() : "") + print(*t.args[k], 1);
        return s + ")";
      }
    }
    return "?";
  }

  std::string binary(const Tree& t, const char* op, int left, int right) {
    return print(*t.args[0], left) + space() + op + space() + print(*t.args[1], right);
  }

  test::Random rng_;
};

bool has_coordinates(const Tree& t) {
  if (t.kind == K::X || t.kind == K::Y || t.kind == K::Z) return true;
  for (const auto& a : t.args)
    if (has_coordinates(*a)) return true;
  return false;
}

// min and max as documented: a NaN argument ignored, the first argument kept on ties.
Real min2(Real a, Real b) { return std::isnan(a) ? b : std::isnan(b) ? a : b < a ? b : a; }
Real max2(Real a, Real b) { return std::isnan(a) ? b : std::isnan(b) ? a : b > a ? b : a; }

// The documented semantics, written with the C library directly.
Real direct(const Tree& t, const Vec3& p) {
  auto arg = [&](int k) { return direct(*t.args[std::size_t(k)], p); };
  switch (t.kind) {
    case K::X: return p.x;
    case K::Y: return p.y;
    case K::Z: return p.z;
    case K::Const: return t.value;
    case K::Pi: return 3.14159265358979323846;
    case K::ParamA: return kA;
    case K::ParamB: return kB;
    case K::Neg: return -arg(0);
    case K::Plus: return arg(0);
    case K::Add: return arg(0) + arg(1);
    case K::Sub: return arg(0) - arg(1);
    case K::Mul: return arg(0) * arg(1);
    case K::Div: return arg(0) / arg(1);
    case K::Pow: case K::Call: break;
  }
  const std::string& f = t.fn;
  if (t.kind == K::Pow || f == "pow") {
    const Real base = arg(0), e = arg(1);
    if (!has_coordinates(*t.args[1]) && e == 2) return base * base;
    if (!has_coordinates(*t.args[1]) && e == 3) return base * base * base;
    return std::pow(base, e);
  }
  if (f == "sin") return std::sin(arg(0));
  if (f == "cos") return std::cos(arg(0));
  if (f == "tan") return std::tan(arg(0));
  if (f == "asin") return std::asin(arg(0));
  if (f == "acos") return std::acos(arg(0));
  if (f == "atan") return std::atan(arg(0));
  if (f == "exp") return std::exp(arg(0));
  if (f == "log") return std::log(arg(0));
  if (f == "sqrt") return std::sqrt(arg(0));
  if (f == "abs") return std::fabs(arg(0));
  if (f == "floor") return std::floor(arg(0));
  if (f == "atan2") return std::atan2(arg(0), arg(1));
  if (f == "mod") return std::fmod(arg(0), arg(1));
  if (f == "clamp") return min2(max2(arg(0), arg(1)), arg(2));
  Real r = arg(0);
  for (int k = 1; k < int(t.args.size()); ++k) r = f == "min" ? min2(r, arg(k)) : max2(r, arg(k));
  return r;
}

bool same(Real a, Real b) { return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0; }

const ExpressionParameters kParameters = {{"a", kA}, {"b", kB}};

TEST(Expression, RandomTreesAgreeWithDirectEvaluation) {
  Generator gen(2024);
  Printer printer(7);
  test::Random points(99);
  int compiled = 0, finite = 0;
  for (int n = 0; n < 3000; ++n) {
    const auto tree = gen.make(1 + n % 6);
    const std::string text = printer.print(*tree, 1);
    Expression e;
    try {
      e = compile_expression(text, kParameters);
    } catch (const ExpressionError& err) {
      ADD_FAILURE() << text << ": " << err.what();
      continue;
    }
    ++compiled;
    for (int k = 0; k < 8; ++k) {
      const Vec3 p = k == 0 ? Vec3(0) : k == 1 ? Vec3(2, 3, -1) : points.point(-3, 3);
      const Real want = direct(*tree, p), got = kernel::evaluate(e, p);
      finite += std::isfinite(want);
      ASSERT_TRUE(same(want, got)) << text << " at (" << p.x << ", " << p.y << ", " << p.z << "): C++ " << want
                                   << ", compiled " << got;
    }
  }
  EXPECT_EQ(compiled, 3000);
  EXPECT_GT(finite, 3000 * 8 / 2);  // most values are ordinary numbers, not NaN or infinities
}

// Squared terms added to what comes before them, and sqrt/sin/cos, have fused operations of
// their own: the distance of the shapes-pov isosurface is four operations, and every such
// program gives the postfix program's values bit for bit.
TEST(Expression, SquaredTermsAddWithoutAPush) {
  const struct {
    const char* text;
    int fused;
  } cases[] = {
      {"sqrt((x - 0.15)^2 + (y - 0.6)^2 + (z + 1)^2) - 0.55 + 0.03*sin(20*y)", 10},
      {"(x - 1)^2 + (y + 2)^2", 2},
      {"cos(x) + (y - 1)^2 + (x + 2)^2 - (z - 3)^2", 7},
      {"(z + 0.5)^2 * 3 + sin((x - 2)^2)", 5},
  };
  test::Random points(7);
  for (const auto& c : cases) {
    const Expression e = compile_expression(c.text);
    EXPECT_EQ(e.fused_length, c.fused) << c.text;
    for (int k = 0; k < 2000; ++k) {
      const Vec3 p = points.point(-3, 3);
      const Real want = kernel::evaluate_postfix(e, p), got = kernel::evaluate(e, p);
      ASSERT_TRUE(same(want, got)) << c.text << " at (" << p.x << ", " << p.y << ", " << p.z << "): " << want
                                   << " != " << got;
    }
  }
}

Real eval(const std::string& text, Vec3 p = Vec3(0), const ExpressionParameters& params = {}) {
  return kernel::evaluate(compile_expression(text, params), p);
}

TEST(Expression, Precedence) {
  EXPECT_EQ(eval("-2^2"), -4);
  EXPECT_EQ(eval("2^3^2"), 512);
  EXPECT_EQ(eval("2^-1"), 0.5);
  EXPECT_EQ(eval("8/4/2"), 1);
  EXPECT_EQ(eval("2-3-4"), -5);
  EXPECT_EQ(eval("2+3*4"), 14);
  EXPECT_EQ(eval("(2+3)*4"), 20);
  EXPECT_EQ(eval("- -x", Vec3(3, 0, 0)), 3);
  EXPECT_EQ(eval("-x^2", Vec3(3, 0, 0)), -9);
  EXPECT_EQ(eval("2*-y", Vec3(0, 4, 0)), -8);
  EXPECT_EQ(eval("min(3, z, 1, 2)", Vec3(0, 0, 5)), 1);
  EXPECT_EQ(eval("max(1, z)", Vec3(0, 0, 5)), 5);
  EXPECT_EQ(eval("clamp(x, -1, 1)", Vec3(7, 0, 0)), 1);
  EXPECT_EQ(eval("mod(-7, 3)"), -1);  // fmod: the sign of the dividend
  EXPECT_EQ(eval("floor(-0.5)"), -1);
  EXPECT_EQ(eval("k * x + .5e1", Vec3(2, 0, 0), {{"k", 3}}), 11);
  EXPECT_DOUBLE_EQ(eval("atan2(1, 0)"), kPi / 2);
  EXPECT_EQ(eval("pi"), kPi);
}

TEST(Expression, ConstantsFoldAndSquaresMultiply) {
  const Expression e = compile_expression("2*3 + x^2 + sqrt(4)^3");
  // ((2·3) + x²) + 2³, left to right: 6 x Square Add 8 Add.
  ASSERT_EQ(e.length, 6);
  EXPECT_EQ(e.code[0].op, kernel::Op::Const);
  EXPECT_EQ(e.code[2].op, kernel::Op::Square);
  EXPECT_EQ(e.constant_count, 2);
  EXPECT_EQ(eval("2*3 + x^2 + sqrt(4)^3", Vec3(3, 0, 0)), 23);
  EXPECT_EQ(compile_expression("sin(pi/2) * cos(0) + 1").length, 1);
  EXPECT_EQ(compile_expression("pow(x, 1 + 2)").code[1].op, kernel::Op::Cube);
  EXPECT_FALSE(uses_coordinates(compile_expression("1 + a", {{"a", 2}})));
  EXPECT_TRUE(uses_coordinates(compile_expression("0*z")));  // not simplified: 0·inf is NaN
}

TEST(Expression, CommutativeOperandsKeepTheStackShallow) {
  // y + (z * (x + (...))): 60 terms leaning right; with the deeper operand first, 2 slots do.
  std::string chain = "x";
  Real want = 1.5;
  for (int k = 0; k < 59; ++k) {
    chain = (k % 3 == 0 ? "y + (" : k % 3 == 1 ? "z * (" : "x + (") + chain + ")";
    want = k % 3 == 0 ? 2 + want : k % 3 == 1 ? -0.5 * want : 1.5 + want;
  }
  const Expression e = compile_expression(chain);
  EXPECT_EQ(e.stack_depth, 2);
  EXPECT_EQ(kernel::evaluate(e, Vec3(1.5, 2, -0.5)), want);
  // Subtraction does not commute: y - (y - (...)) needs one slot per level.
  auto differences = [](int n) {
    std::string d = "x";
    for (int k = 1; k < n; ++k) d = "y - (" + d + ")";
    return d;
  };
  EXPECT_EQ(compile_expression(differences(kernel::kMaxExpressionStack)).stack_depth, kernel::kMaxExpressionStack);
  try {
    compile_expression(differences(kernel::kMaxExpressionStack + 1));
    ADD_FAILURE() << "a subtraction chain needing 33 stack slots compiled";
  } catch (const ExpressionError& err) {
    EXPECT_STREQ(err.what(), "column 1: the expression nests too deeply: it needs a stack of 33 values (at most 32)");
  }
}

struct BadExpression {
  std::string text;
  int column;
  std::string message;  // a fragment of it
};

std::string repeat(const std::string& s, int n) {
  std::string r;
  for (int k = 0; k < n; ++k) r += s;
  return r;
}

TEST(Expression, EveryErrorNamesItsColumn) {
  std::string constants = "x";
  for (int k = 1; k <= kernel::kMaxExpressionConstants + 1; ++k) constants += " + " + std::to_string(k);
  const BadExpression cases[] = {
      {"", 1, "the expression is empty"},
      {"   ", 4, "the expression is empty"},
      {"x + #", 5, "unexpected character '#'"},
      {"x + \xc3\xa9", 5, "unexpected character (byte 195)"},
      {"x + 1e+", 5, "malformed number '1e+'"},
      {"1.2.3 * x", 1, "malformed number '1.2.3'"},
      {"2 + 1e999", 5, "number '1e999' is out of range"},
      {"x +", 4, "unexpected end of the expression: expected a number, a name or '('"},
      {"x y", 3, "expected an operator or the end of the expression, found 'y'"},
      {"2x", 2, "expected an operator or the end of the expression, found 'x'"},
      {"* x", 1, "expected a number, a name or '(', found '*'"},
      {"(x + 1", 1, "'(' is never closed"},
      {"(x + 1 y", 8, "expected ')' or an operator, found 'y'"},
      {"x)", 2, "')' without a matching '('"},
      {"x + foo", 5, "unknown name 'foo' (known: x, y, z, pi, a, b)"},
      {"1 + foo(x)", 5, "unknown function 'foo' (functions: sin cos tan asin acos atan exp log sqrt abs floor atan2 pow mod min max clamp)"},
      {"sin(x, y)", 1, "sin takes 1 argument, got 2"},
      {"2 * atan2(x)", 5, "atan2 takes 2 arguments, got 1"},
      {"min(x)", 1, "min takes at least 2 arguments, got 1"},
      {"clamp(x, 1, 2, 3)", 1, "clamp takes 3 arguments, got 4"},
      {"sin + 1", 1, "'sin' is a function: write sin(...)"},
      {"x(1)", 1, "'x' is not a function"},
      {"sin(x", 4, "'(' is never closed"},
      {"sin()", 5, "expected a number, a name or '(', found ')'"},
      {"max(x,)", 7, "expected a number, a name or '(', found ')'"},
      {repeat("(", 65) + "x" + repeat(")", 65), 65, "nests too deeply (at most 64 levels)"},
      {repeat("-", 65) + "x", 65, "nests too deeply (at most 64 levels)"},
      {"x" + repeat("+x", 600), 1024, "too long (at most 1024 numbers, names and operators)"},
      {"x*y" + repeat(" + x*y", 129), 1, "too long: more than 256 operations after folding constants"},
      {constants, 1, "too many different constants (at most 64)"},
  };
  for (const BadExpression& c : cases) {
    const std::string shown = c.text.substr(0, 40);
    try {
      compile_expression(c.text, kParameters);
      ADD_FAILURE() << "'" << shown << "' compiled";
    } catch (const ExpressionError& err) {
      EXPECT_EQ(err.column(), c.column) << shown << ": " << err.what();
      EXPECT_NE(err.message().find(c.message), std::string::npos) << shown << ": " << err.what();
      EXPECT_EQ(std::string(err.what()), "column " + std::to_string(c.column) + ": " + err.message());
    }
  }
}

TEST(Expression, ParameterNames) {
  EXPECT_TRUE(valid_parameter_name("radius_2"));
  EXPECT_TRUE(valid_parameter_name("_k"));
  for (const char* bad : {"", "x", "pi", "sin", "2a", "a-b", "a b"}) EXPECT_FALSE(valid_parameter_name(bad)) << bad;
}

}  // namespace
}  // namespace strahl::expression_test
