// Recursive-descent parser of the implicit-surface expression language (grammar in
// expression_compiler.h). Every error names the column where the offending token starts.

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

#include "strahl/scene/expression_ast.h"

namespace strahl::expression {
namespace {

using kernel::Op;

struct Function {
  std::string_view name;
  Op op;
  int min_args, max_args;  // max_args = 0: any number from min_args on (folded pairwise, left to right)
};

constexpr Function kFunctions[] = {
    {"sin", Op::Sin, 1, 1},     {"cos", Op::Cos, 1, 1},   {"tan", Op::Tan, 1, 1},   {"asin", Op::Asin, 1, 1},
    {"acos", Op::Acos, 1, 1},   {"atan", Op::Atan, 1, 1}, {"exp", Op::Exp, 1, 1},   {"log", Op::Log, 1, 1},
    {"sqrt", Op::Sqrt, 1, 1},   {"abs", Op::Abs, 1, 1},   {"floor", Op::Floor, 1, 1}, {"atan2", Op::Atan2, 2, 2},
    {"pow", Op::Pow, 2, 2},     {"mod", Op::Mod, 2, 2},   {"min", Op::Min, 2, 0},   {"max", Op::Max, 2, 0},
    {"clamp", Op::Clamp, 3, 3},
};

const Function* find_function(std::string_view name) {
  for (const Function& f : kFunctions)
    if (f.name == name) return &f;
  return nullptr;
}

std::string function_list() {
  std::string s;
  for (const Function& f : kFunctions) s += (s.empty() ? "" : " ") + std::string(f.name);
  return s;
}

enum class Tok { Number, Name, Plus, Minus, Star, Slash, Caret, Open, Close, Comma, End };

struct Token {
  Tok kind = Tok::End;
  std::string_view text;
  int column = 1;
  Real value = 0;
};

bool name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool digit(char c) { return c >= '0' && c <= '9'; }

class Parser {
 public:
  Parser(std::string_view text, const ExpressionParameters& parameters) : text_(text), parameters_(parameters) {
    advance();
  }

  Tree run() {
    if (tok_.kind == Tok::End) fail(tok_.column, "the expression is empty");
    tree_.root = sum();
    if (tok_.kind == Tok::Close) fail(tok_.column, "')' without a matching '('");
    if (tok_.kind != Tok::End) fail(tok_.column, "expected an operator or the end of the expression, found " + shown(tok_));
    return std::move(tree_);
  }

 private:
  [[noreturn]] static void fail(int column, const std::string& message) { throw ExpressionError(column, message); }

  static std::string shown(const Token& t) {
    return t.kind == Tok::End ? "the end of the expression" : "'" + std::string(t.text) + "'";
  }

  // ---- lexer ----
  void advance() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    tok_ = Token{};
    tok_.column = int(pos_) + 1;
    if (pos_ >= text_.size()) return;
    const std::size_t start = pos_;
    const char c = text_[pos_];
    if (digit(c) || (c == '.' && pos_ + 1 < text_.size() && digit(text_[pos_ + 1]))) return number(start);
    if (name_start(c)) {
      while (pos_ < text_.size() && name_char(text_[pos_])) ++pos_;
      tok_.kind = Tok::Name;
      tok_.text = text_.substr(start, pos_ - start);
      return;
    }
    ++pos_;
    tok_.text = text_.substr(start, 1);
    switch (c) {
      case '+': tok_.kind = Tok::Plus; return;
      case '-': tok_.kind = Tok::Minus; return;
      case '*': tok_.kind = Tok::Star; return;
      case '/': tok_.kind = Tok::Slash; return;
      case '^': tok_.kind = Tok::Caret; return;
      case '(': tok_.kind = Tok::Open; return;
      case ')': tok_.kind = Tok::Close; return;
      case ',': tok_.kind = Tok::Comma; return;
      default: break;
    }
    const unsigned char u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) fail(tok_.column, "unexpected character '" + std::string(1, c) + "'");
    fail(tok_.column, "unexpected character (byte " + std::to_string(unsigned(u)) + ")");
  }

  // digits [. digits] [e [+-] digits], or . digits [...]; a second '.' or a bare exponent is malformed.
  void number(std::size_t start) {
    while (pos_ < text_.size() && digit(text_[pos_])) ++pos_;
    if (pos_ < text_.size() && text_[pos_] == '.') {
      ++pos_;
      while (pos_ < text_.size() && digit(text_[pos_])) ++pos_;
    }
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      std::size_t p = pos_ + 1;
      if (p < text_.size() && (text_[p] == '+' || text_[p] == '-')) ++p;
      if (p < text_.size() && digit(text_[p])) {
        while (p < text_.size() && digit(text_[p])) ++p;
        pos_ = p;
      } else if (p > pos_ + 1) {  // "1e+" or "1e-": an exponent sign without digits
        malformed(start, p);
      }
    }
    if (pos_ < text_.size() && (text_[pos_] == '.' || digit(text_[pos_]))) malformed(start, pos_ + 1);
    tok_.kind = Tok::Number;
    tok_.text = text_.substr(start, pos_ - start);
    const char* first = text_.data() + start;
    const auto [end, ec] = std::from_chars(first, text_.data() + pos_, tok_.value);
    if (ec == std::errc::result_out_of_range || !std::isfinite(tok_.value))
      fail(tok_.column, "number '" + std::string(tok_.text) + "' is out of range");
    if (ec != std::errc() || end != text_.data() + pos_) malformed(start, pos_);
  }

  [[noreturn]] void malformed(std::size_t start, std::size_t end) const {
    while (end < text_.size() && (name_char(text_[end]) || text_[end] == '.')) ++end;
    fail(int(start) + 1, "malformed number '" + std::string(text_.substr(start, end - start)) + "'");
  }

  // ---- tree ----
  int add(Op op, int column, int a = -1, int b = -1, int c = -1, Real value = 0) {
    if (int(tree_.nodes.size()) >= kMaxExpressionNodes)
      fail(column, "the expression is too long (at most " + std::to_string(kMaxExpressionNodes) +
                       " numbers, names and operators)");
    Node n;
    n.op = op;
    n.value = value;
    n.column = column;
    n.child[0] = a;
    n.child[1] = b;
    n.child[2] = c;
    tree_.nodes.push_back(n);
    return int(tree_.nodes.size()) - 1;
  }

  struct Nest {
    explicit Nest(Parser& p) : parser(p) {
      if (++parser.depth_ > kMaxExpressionNesting)
        fail(parser.tok_.column,
             "the expression nests too deeply (at most " + std::to_string(kMaxExpressionNesting) + " levels)");
    }
    ~Nest() { --parser.depth_; }
    Parser& parser;
  };

  // ---- grammar ----
  int sum() {
    int left = product();
    while (tok_.kind == Tok::Plus || tok_.kind == Tok::Minus) {
      const Op op = tok_.kind == Tok::Plus ? Op::Add : Op::Sub;
      const int column = tok_.column;
      advance();
      left = add(op, column, left, product());
    }
    return left;
  }

  int product() {
    int left = unary();
    while (tok_.kind == Tok::Star || tok_.kind == Tok::Slash) {
      const Op op = tok_.kind == Tok::Star ? Op::Mul : Op::Div;
      const int column = tok_.column;
      advance();
      left = add(op, column, left, unary());
    }
    return left;
  }

  int unary() {
    if (tok_.kind == Tok::Minus || tok_.kind == Tok::Plus) {
      const Nest nest(*this);
      const bool negate = tok_.kind == Tok::Minus;
      const int column = tok_.column;
      advance();
      const int operand = unary();
      return negate ? add(Op::Neg, column, operand) : operand;
    }
    return power();
  }

  int power() {
    const int base = primary();
    if (tok_.kind != Tok::Caret) return base;
    const int column = tok_.column;
    advance();
    const Nest nest(*this);
    return add(Op::Pow, column, base, unary());
  }

  int primary() {
    const Token t = tok_;
    switch (t.kind) {
      case Tok::Number: advance(); return add(Op::Const, t.column, -1, -1, -1, t.value);
      case Tok::Open: {
        const Nest nest(*this);
        advance();
        const int inner = sum();
        if (tok_.kind != Tok::Close) unclosed(t);
        advance();
        return inner;
      }
      case Tok::Name: return name();
      case Tok::End: fail(t.column, "unexpected end of the expression: expected a number, a name or '('");
      default: fail(t.column, "expected a number, a name or '(', found " + shown(t));
    }
  }

  [[noreturn]] void unclosed(const Token& open) const {
    if (tok_.kind == Tok::End) fail(open.column, "'(' is never closed");
    fail(tok_.column, "expected ')' or an operator, found " + shown(tok_));
  }

  int name() {
    const Token t = tok_;
    advance();
    const Function* f = find_function(t.text);
    if (tok_.kind == Tok::Open) {
      if (!f) {
        if (variable(t.text) || parameters_.count(t.text)) fail(t.column, "'" + std::string(t.text) + "' is not a function");
        fail(t.column, "unknown function '" + std::string(t.text) + "' (functions: " + function_list() + ")");
      }
      return call(t, *f);
    }
    if (f) fail(t.column, "'" + std::string(t.text) + "' is a function: write " + std::string(t.text) + "(...)");
    if (t.text == "x") return add(Op::X, t.column);
    if (t.text == "y") return add(Op::Y, t.column);
    if (t.text == "z") return add(Op::Z, t.column);
    if (t.text == "pi") return add(Op::Const, t.column, -1, -1, -1, kPi);
    const auto it = parameters_.find(t.text);
    if (it != parameters_.end()) return add(Op::Const, t.column, -1, -1, -1, it->second);
    std::string known = "x, y, z, pi";
    for (const auto& kv : parameters_) known += ", " + kv.first;
    fail(t.column, "unknown name '" + std::string(t.text) + "' (known: " + known + ")");
  }

  static bool variable(std::string_view n) { return n == "x" || n == "y" || n == "z" || n == "pi"; }

  int call(const Token& name, const Function& f) {
    const Nest nest(*this);
    const Token open = tok_;
    advance();
    int args[3] = {-1, -1, -1};
    int count = 0;
    int folded = -1;  // min/max: the pairwise fold so far
    for (;;) {
      const int arg = sum();
      ++count;
      if (f.max_args == 0) {
        folded = folded < 0 ? arg : add(f.op, name.column, folded, arg);
      } else if (count <= f.max_args) {
        args[count - 1] = arg;
      }
      if (tok_.kind != Tok::Comma) break;
      advance();
    }
    if (tok_.kind != Tok::Close) unclosed(open);
    const bool too_few = count < f.min_args, too_many = f.max_args > 0 && count > f.max_args;
    if (too_few || too_many) {
      const std::string wanted = f.max_args == 0             ? "at least " + std::to_string(f.min_args)
                                 : f.min_args == f.max_args ? std::to_string(f.min_args)
                                                            : std::to_string(f.min_args) + " to " + std::to_string(f.max_args);
      fail(name.column, std::string(f.name) + " takes " + wanted + (f.min_args == 1 && f.max_args == 1 ? " argument" : " arguments") +
                            ", got " + std::to_string(count));
    }
    advance();
    if (f.max_args == 0) return folded;
    return add(f.op, name.column, args[0], args[1], args[2]);
  }

  std::string_view text_;
  const ExpressionParameters& parameters_;
  std::size_t pos_ = 0;
  Token tok_;
  int depth_ = 0;
  Tree tree_;
};

}  // namespace

Tree parse(std::string_view text, const ExpressionParameters& parameters) { return Parser(text, parameters).run(); }

}  // namespace strahl::expression

namespace strahl {

bool valid_parameter_name(std::string_view name) {
  if (name.empty() || !expression::name_start(name[0])) return false;
  for (char c : name)
    if (!expression::name_char(c)) return false;
  return name != "x" && name != "y" && name != "z" && name != "pi" && !expression::find_function(name);
}

}  // namespace strahl
