#pragma once
// The parse tree of an expression (scene/expression_compiler.h): what the parser builds and the
// compiler folds and flattens into postfix code. Internal to those two.

#include <string_view>
#include <vector>

#include "strahl/geometry/expression.h"
#include "strahl/scene/expression_compiler.h"

namespace strahl::expression {

struct Node {
  kernel::Op op = kernel::Op::Const;
  Real value = 0;            // Const
  int column = 1;            // where it starts in the text (1-based), for messages
  int child[3] = {-1, -1, -1};
};

struct Tree {
  std::vector<Node> nodes;  // children before their parents
  int root = -1;
};

// Throws ExpressionError.
Tree parse(std::string_view text, const ExpressionParameters& parameters);

}  // namespace strahl::expression
