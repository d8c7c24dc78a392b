#pragma once
// The expression language of implicit surfaces (docs/scene-format.md, "implicit"): text such as
// `sqrt(x^2 + z^2) - 0.5 + a*sin(8*y)` compiled once into the fixed-size postfix program of
// geometry/expression.h. Orchestration code: it allocates and throws.
//
// Grammar (usual precedence; ^ binds tighter than unary minus and is right-associative, so
// -x^2 = -(x^2) and 2^3^2 = 2^9):
//   sum     := product (('+' | '-') product)*
//   product := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power
//   power   := primary ('^' unary)?
//   primary := number | name | function '(' sum (',' sum)* ')' | '(' sum ')'
// Names: x, y, z, pi and the parameters given. Functions: sin cos tan asin acos atan exp log
// sqrt abs floor (1 argument), atan2 pow mod (2), clamp (3), min max (2 or more).
// Subexpressions without x, y and z are folded into constants, evaluated exactly as the kernel
// would; + and * may swap their operands (exact in IEEE arithmetic) to keep the stack shallow.

#include <map>
#include <string>
#include <string_view>

#include "strahl/geometry/expression.h"
#include "strahl/util/error.h"

namespace strahl {

// A mistake in the expression, at a 1-based column of its text. what() is "column N: message";
// message() is the message alone, for callers that put the column into a file location.
class ExpressionError : public Error {
 public:
  ExpressionError(int column, const std::string& message)
      : Error("column " + std::to_string(column) + ": " + message), column_(column), message_(message) {}
  int column() const { return column_; }
  const std::string& message() const { return message_; }

 private:
  int column_;
  std::string message_;
};

using ExpressionParameters = std::map<std::string, Real, std::less<>>;

// Most nodes (numbers, names, operators, calls) an expression may have before folding, and the
// deepest nesting of parentheses, calls and unary signs: bounds on the compiler's own work.
inline constexpr int kMaxExpressionNodes = 1024;
inline constexpr int kMaxExpressionNesting = 64;

// Throws ExpressionError for a syntax error, an unknown name or function, a wrong argument count,
// or an expression beyond the bounds above or in geometry/expression.h.
kernel::Expression compile_expression(std::string_view text, const ExpressionParameters& parameters = {});

// Whether the program reads x, y or z (an expression that does not describes no surface).
bool uses_coordinates(const kernel::Expression& e);

// A name may be a parameter when it is an identifier and not x, y, z, pi or a function's name.
bool valid_parameter_name(std::string_view name);

}  // namespace strahl
