// The POV-Ray importer's values (pov_parser.h): float and vector expressions with POV-Ray's
// precedence, its functions and random streams, strings, colours, and declarable values.

#include "strahl/scene/pov/pov_parser.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace strahl::pov {

Value Parser::value() {
  const Token& t = peek();
  if (t.kind == TokenKind::Identifier) {
    if (t.text == "pigment" || t.text == "finish" || t.text == "interior" || t.text == "texture") {
      next();
      Value v;
      v.kind = t.text == "pigment" ? Value::Kind::Pigment : t.text == "finish" ? Value::Kind::Finish
               : t.text == "interior" ? Value::Kind::Interior : Value::Kind::Texture;
      const std::string what = t.text;
      texture_block(what, v.texture);
      if (what == "texture" && skip_layers()) {
        const Noting noting(*this, v.texture);
        note(loc(t), "a layered texture is drawn as its first layer");
      }
      return v;
    }
    if (is_shape(t.text)) {
      const Token kw = next();
      Value v;
      v.kind = Value::Kind::Object;
      v.object = std::make_shared<const Object>(object(kw));
      return v;
    }
    if (t.text == "color" || t.text == "colour" || t.text.rfind("rgb", 0) == 0) {
      Value v;
      const Color c = color();
      v.num.c = c;
      v.num.dim = 5;
      return v;
    }
    if (const auto it = symbols_.find(t.text); it != symbols_.end() && it->second.kind != Value::Kind::Number) {
      next();
      return it->second;
    }
    if (is_macro(t)) {
      const Token name = next();
      const std::size_t depth = controls_.size();
      call_macro(name);
      Value v = value();
      finish_macro(depth, name);
      return v;
    }
  }
  if (t.kind == TokenKind::String || (t.kind == TokenKind::Identifier && (t.text == "concat" || t.text == "str" || t.text == "chr"))) {
    Value v;
    v.kind = Value::Kind::String;
    v.str = string_value();
    return v;
  }
  Value v;
  v.num = expression();
  return v;
}

double Parser::symbol_number(const std::string& name, const FileLoc& loc) {
  const auto it = symbols_.find(name);
  if (it == symbols_.end() || it->second.kind != Value::Kind::Number) throw Error(loc, "'" + name + "' is not a float");
  return it->second.num.f();
}

Num Parser::expression() {
  const Nesting n(*this, raw());
  return conditional();
}

Num Parser::conditional() {
  Num c = logical_or();
  if (accept_raw_symbol("?")) {
    const Num a = conditional();
    expect_symbol(":", "in a ? : expression");
    const Num b = conditional();
    return c.f() != 0 ? a : b;
  }
  return c;
}

Num Parser::logical_or() {
  Num a = logical_and();
  while (accept_raw_symbol("|")) a = number(a.f() != 0 || logical_and().f() != 0);
  return a;
}

Num Parser::logical_and() {
  Num a = comparison();
  while (accept_raw_symbol("&")) a = number((comparison().f() != 0) && a.f() != 0);
  return a;
}

Num Parser::comparison() {
  Num a = sum();
  for (const char* op : {"<", "<=", ">", ">=", "=", "!="}) {
    if (in_vector_ > 0 && (std::string(op) == ">" )) continue;  // '>' closes a vector literal
    if (accept_raw_symbol(op)) {
      const double b = sum().f(), x = a.f();
      const std::string o = op;
      return number(o == "<" ? x < b : o == "<=" ? x <= b : o == ">" ? x > b : o == ">=" ? x >= b : o == "=" ? x == b : x != b);
    }
  }
  return a;
}

Num Parser::sum() {
  Num a = product();
  for (;;) {
    if (accept_raw_symbol("+")) a = combine(a, product(), [](double x, double y) { return x + y; });
    else if (accept_raw_symbol("-")) a = combine(a, product(), [](double x, double y) { return x - y; });
    else return a;
  }
}

Num Parser::product() {
  Num a = unary();
  for (;;) {
    if (accept_raw_symbol("*")) a = combine(a, unary(), [](double x, double y) { return x * y; });
    else if (accept_raw_symbol("/")) a = combine(a, unary(), [](double x, double y) { return x / y; });
    else return a;
  }
}

Num Parser::combine(const Num& a, const Num& b, const std::function<double(double, double)>& f) {
  Num r;
  r.dim = std::max(a.dim, b.dim);
  for (int i = 0; i < r.dim; ++i) r.c[std::size_t(i)] = f(a.dim == 1 ? a.c[0] : a.c[std::size_t(i)], b.dim == 1 ? b.c[0] : b.c[std::size_t(i)]);
  return r;
}

Num Parser::unary() {
  const Nesting n(*this, raw());
  if (accept_symbol("-")) return combine(number(0), unary(), [](double, double y) { return -y; });
  if (accept_symbol("+")) return unary();
  if (accept_symbol("!")) return number(unary().f() == 0);
  return postfix(primary());
}

Num Parser::postfix(Num v) {
  while (is_symbol(raw(), ".") && pos_ + 1 < tokens_.size() && tokens_[pos_ + 1].kind == TokenKind::Identifier) {
    const Token field = tokens_[pos_ + 1];
    static const std::map<std::string, int> kFields = {{"x", 0}, {"u", 0}, {"red", 0}, {"y", 1}, {"v", 1}, {"green", 1},
                                                       {"z", 2}, {"blue", 2}, {"t", 3}, {"filter", 3}, {"transmit", 4}};
    const auto it = kFields.find(field.text);
    if (it == kFields.end()) throw Error(loc(field), "unknown component ." + field.text);
    pos_ += 2;
    v = number(v.dim == 1 ? v.c[0] : v.c[std::size_t(it->second)]);
  }
  return v;
}

Num Parser::primary() {
  const Token t = next();
  if (t.kind == TokenKind::Number) return number(t.number);
  if (is_symbol(t, "(")) {
    const int saved = in_vector_;
    in_vector_ = 0;
    Num v = expression();
    in_vector_ = saved;
    expect_symbol(")", "to close '('");
    return v;
  }
  if (is_symbol(t, "<")) {
    Num v;
    v.dim = 0;
    ++in_vector_;
    do {
      if (v.dim == 5) throw Error(loc(t), "a vector has at most 5 components");
      v.c[std::size_t(v.dim++)] = expression().f();
    } while (accept_symbol(","));
    --in_vector_;
    expect_symbol(">", "to close the vector");
    if (v.dim < 2) throw Error(loc(t), "a vector needs at least 2 components");
    return v;
  }
  if (t.kind != TokenKind::Identifier) throw Error(loc(t), "expected a number or vector, found " + describe(t));
  const std::string& n = t.text;
  if (n == "x") return vector_num({1, 0, 0});
  if (n == "y") return vector_num({0, 1, 0});
  if (n == "z") return vector_num({0, 0, 1});
  if (n == "pi") return number(kPi);
  if (n == "true" || n == "yes" || n == "on") return number(1);
  if (n == "false" || n == "no" || n == "off") return number(0);
  if (n == "image_width") return number(options_.width);
  if (n == "image_height") return number(options_.height);
  if (n == "clock") return number(0);
  if (n == "clock_delta") return number(1);
  if (n == "version") return number(3.7);
  if (n == "color" || n == "colour" || n.rfind("rgb", 0) == 0) {
    --pos_;
    Num v;
    v.c = color();
    v.dim = 5;
    return v;
  }
  if (const auto it = symbols_.find(n); it != symbols_.end()) {
    if (it->second.kind != Value::Kind::Number) throw Error(loc(t), "'" + n + "' is not a number or vector here");
    return it->second.num;
  }
  if (is_macro(t)) {
    const std::size_t depth = controls_.size();
    call_macro(t);
    const int saved = in_vector_;
    in_vector_ = 0;
    const Num v = expression();
    in_vector_ = saved;
    finish_macro(depth, t);
    return v;
  }
  if (is_symbol(peek(), "(")) return function(t);
  throw Error(loc(t), "unknown name '" + n + "' (not declared)");
}

Num Parser::function(const Token& t) {
  expect_symbol("(", "after a function name");
  std::vector<Num> args;
  const int saved = in_vector_;
  in_vector_ = 0;
  if (!accept_symbol(")")) {
    do args.push_back(expression());
    while (accept_symbol(","));
    expect_symbol(")", ("to close " + t.text + "(").c_str());
  }
  in_vector_ = saved;
  const std::string& n = t.text;
  auto need = [&](std::size_t k) {
    if (args.size() != k) throw Error(loc(t), n + "() takes " + std::to_string(k) + " argument" + (k == 1 ? "" : "s"));
  };
  static const std::map<std::string, double (*)(double)> kOne = {
      {"sin", std::sin},   {"cos", std::cos},   {"tan", std::tan},   {"asin", std::asin}, {"acos", std::acos},
      {"atan", std::atan}, {"sqrt", std::sqrt}, {"exp", std::exp},   {"log", std::log},   {"abs", std::fabs},
      {"floor", std::floor}, {"ceil", std::ceil}, {"sinh", std::sinh}, {"cosh", std::cosh}, {"tanh", std::tanh}};
  if (const auto it = kOne.find(n); it != kOne.end()) {
    need(1);
    return number(it->second(args[0].f()));
  }
  if (n == "radians") return need(1), number(args[0].f() * kPi / 180);
  if (n == "degrees") return need(1), number(args[0].f() * 180 / kPi);
  if (n == "int") return need(1), number(std::trunc(args[0].f()));
  if (n == "pow") return need(2), number(std::pow(args[0].f(), args[1].f()));
  if (n == "atan2") return need(2), number(std::atan2(args[0].f(), args[1].f()));
  if (n == "mod") return need(2), number(std::fmod(args[0].f(), args[1].f()));
  if (n == "min" || n == "max") {
    if (args.empty()) need(2);
    double r = args[0].f();
    for (const Num& a : args) r = n == "min" ? std::min(r, a.f()) : std::max(r, a.f());
    return number(r);
  }
  if (n == "seed") {
    // POV-Ray's random streams: seed(n) starts one (its number), rand(stream) draws from it.
    need(1);
    streams_.push_back(static_cast<std::uint32_t>(static_cast<std::int64_t>(whole(args[0].f(), INT32_MIN, INT32_MAX))));
    return number(double(streams_.size() - 1));
  }
  if (n == "rand") {
    need(1);
    const double i = args[0].f();
    if (!(i >= 0 && i < double(streams_.size()))) throw Error(loc(t), "rand() needs a stream made by seed()");
    std::uint32_t& state = streams_[std::size_t(i)];
    state = state * 1812433253u + 12345u;  // (POV-Ray's generator: the same numbers)
    return number(double(state) / 4294967295.0);
  }
  if (n == "vlength") return need(1), number(length(to_vector(args[0])));
  if (n == "vnormalize") {
    need(1);
    const Vector v = to_vector(args[0]);
    const double l = length(v);
    return vector_num({v[0] / l, v[1] / l, v[2] / l});
  }
  if (n == "vdot") {
    need(2);
    const Vector a = to_vector(args[0]), b = to_vector(args[1]);
    return number(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
  }
  if (n == "vcross") {
    need(2);
    const Vector a = to_vector(args[0]), b = to_vector(args[1]);
    return vector_num({a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]});
  }
  throw Error(loc(t), "unknown function '" + n + "' (not supported by strahl's POV-Ray importer)");
}

// Whether `t` begins a float (an optional value such as metallic's).
bool Parser::starts_value(const Token& t) const {
  if (t.kind == TokenKind::Number) return true;
  if (t.kind == TokenKind::Symbol) return t.text == "(" || t.text == "-" || t.text == "+" || t.text == "!";
  if (t.kind != TokenKind::Identifier) return false;
  const auto it = symbols_.find(t.text);
  return (it != symbols_.end() && it->second.kind == Value::Kind::Number) || is_macro(t) || t.text == "pi";
}

// A string: "text", a declared string, concat(…), str(float, width, digits), chr(code).
std::string Parser::string_value() {
  const Token t = next();
  if (t.kind == TokenKind::String) return t.text;
  if (t.kind == TokenKind::Identifier) {
    if (const auto it = symbols_.find(t.text); it != symbols_.end() && it->second.kind == Value::Kind::String) return it->second.str;
    if (t.text == "concat") {
      expect_symbol("(", "after concat");
      std::string s = string_value();
      while (accept_symbol(",")) s += string_value();
      expect_symbol(")", "to close concat(");
      return s;
    }
    if (t.text == "str") {
      expect_symbol("(", "after str");
      const double v = real();
      expect_symbol(",", "in str(value, width, digits)");
      const int width = whole(real(), -64, 64);
      expect_symbol(",", "in str(value, width, digits)");
      const int digits = whole(real(), -1, 32);
      expect_symbol(")", "to close str(");
      char buffer[128];
      std::snprintf(buffer, sizeof buffer, "%*.*f", width < 0 ? -width : width, digits < 0 ? 6 : digits, v);
      return buffer;
    }
    if (t.text == "chr") {
      expect_symbol("(", "after chr");
      const int code = whole(real(), 0, 127);
      expect_symbol(")", "to close chr(");
      return std::string(1, char(code));
    }
  }
  throw Error(loc(t), "expected a string, found " + describe(t));
}

// `color`/`colour` (optional) then rgb, rgbf, rgbt, rgbft and red/green/blue/filter/transmit,
// or any colour expression.
Color Parser::color() {
  if (is_word(peek(), "color") || is_word(peek(), "colour")) next();
  Color c{};
  bool any = false;
  for (;;) {
    const Token& t = peek();
    if (t.kind != TokenKind::Identifier) break;
    const std::string n = t.text;
    if (n == "rgb" || n == "rgbf" || n == "rgbt" || n == "rgbft") {
      next();
      const Num v = expression();
      const std::size_t k = n == "rgb" ? 3 : n == "rgbft" ? 5 : 4;
      Color e{};
      for (std::size_t i = 0; i < k; ++i) e[i] = v.dim == 1 ? v.c[0] : (i < std::size_t(v.dim) ? v.c[i] : 0);
      c = {e[0], e[1], e[2], n == "rgbf" || n == "rgbft" ? e[3] : 0, n == "rgbt" ? e[3] : n == "rgbft" ? e[4] : 0};
      any = true;
    } else if (n == "red" || n == "green" || n == "blue" || n == "filter" || n == "transmit") {
      next();
      const std::size_t i = n == "red" ? 0 : n == "green" ? 1 : n == "blue" ? 2 : n == "filter" ? 3 : 4;
      c[i] = real();
      any = true;
    } else if (!any && (symbols_.count(n) || n == "x" || n == "y" || n == "z")) {
      c = to_color(expression());
      any = true;
    } else {
      break;
    }
  }
  if (!any) {
    const Token& t = peek();
    if (is_symbol(t, "<") || t.kind == TokenKind::Number || is_symbol(t, "(") || is_symbol(t, "-")) return to_color(expression());
    throw Error(loc(t), "expected a colour, found " + describe(t));
  }
  return c;
}

}  // namespace strahl::pov
