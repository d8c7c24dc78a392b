// The POV-Ray importer's parser (pov_reader.h). POV-Ray evaluates its language as it reads it:
// directives are carried out where they stand, so the parser processes them whenever it looks at
// the next token of a statement, an item's body or an expression's first operand. Only what
// docs/pov-import.md lists is read; anything else is an error that names it, or, where leaving it
// out keeps the picture's geometry (bump maps, photons, `no_shadow` …), a warning.

#include "strahl/scene/pov/pov_reader.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "strahl/scene/pov/pov_lexer.h"
#include "strahl/util/number_syntax.h"

namespace strahl::pov {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxIncludes = 256;
constexpr int kMaxNesting = 200;
constexpr std::size_t kMaxTokens = 24'000'000;  // the scene and its includes (~56 bytes each)

// A float (dim 1) or a vector of 2 to 5 components. A float used as a colour sets all five
// components (POV-Ray's rule: `color 0.5` is rgbft <0.5, 0.5, 0.5, 0.5, 0.5>).
struct Num {
  std::array<double, 5> c{};
  int dim = 1;
  double f() const { return c[0]; }
};

struct Value {
  enum class Kind { Number, String, Pigment, Finish, Interior, Texture, Object } kind = Kind::Number;
  Num num;
  std::string str;
  Texture texture;  // Pigment, Finish, Interior and Texture values live in a texture
  std::shared_ptr<const Object> object;
};

Vector to_vector(const Num& n) {
  if (n.dim == 1) return {n.c[0], n.c[0], n.c[0]};
  return {n.c[0], n.c[1], n.c[2]};
}

Color to_color(const Num& n) {
  if (n.dim == 1) return {n.c[0], n.c[0], n.c[0], n.c[0], n.c[0]};
  return {n.c[0], n.c[1], n.c[2], n.dim > 3 ? n.c[3] : 0, n.dim > 4 ? n.c[4] : 0};
}

Num number(double v) {
  Num n;
  n.c[0] = v;
  return n;
}

Num vector_num(const Vector& v) {
  Num n;
  n.c = {v[0], v[1], v[2], 0, 0};
  n.dim = 3;
  return n;
}


// Items that `#declare` may name and `object { NAME }` may use.
const std::set<std::string> kShapes = {"sphere",       "plane",   "box",   "cylinder",  "cone",     "torus",
                                       "disc",         "triangle", "smooth_triangle", "mesh", "mesh2", "isosurface",
                                       "quadric",      "union",        "intersection", "difference", "merge", "object"};

class Reader {
 public:
  Reader(const std::string& text, const std::string& name, const PovOptions& options) : options_(options) {
    tokens_ = text_tokens(text, name);
    for (const auto& [declared, value] : options.declares) symbols_[declared] = Value{Value::Kind::Number, number(value), {}, {}, {}};
  }

  Parsed run() {
    while (peek().kind != TokenKind::End) statement();
    if (!controls_.empty()) throw Error(controls_.back().loc, "this #" + controls_.back().name + " has no #end");
    if (!gamma_given_ && !(version_ >= 3.7))
      out_.warnings.push_back(files_.front() +
                              ": no #version 3.7 and no assumed_gamma: POV-Ray draws this scene with its legacy "
                              "gamma, writing the linear values to 8-bit images (strahl's --linear does the same)");
    return std::move(out_);
  }

 private:
  // ---- tokens and directives ------------------------------------------------------------------

  std::vector<Token> read_tokens(const fs::path& path, const FileLoc& from) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw Error(from.file.empty() ? FileLoc{path.string()} : from, "cannot open '" + path.string() + "' (no such file)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(from.file.empty() ? FileLoc{path.string()} : from, "cannot open '" + path.string() + "'");
    std::ostringstream text;
    text << in.rdbuf();
    return text_tokens(text.str(), path.string());
  }
  std::vector<Token> text_tokens(const std::string& text, const std::string& name) {
    if (const std::size_t nul = text.find('\0'); nul != std::string::npos)
      throw Error(FileLoc{name, 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(nul), '\n'))},
                  "not a text file (a NUL byte; POV-Ray scenes are text)");
    files_.push_back(name);
    return tokenize(text, name, std::uint32_t(files_.size() - 1));
  }

  FileLoc loc(const Token& t) const { return FileLoc{files_[t.file], t.line, t.column}; }

  const Token& raw() const { return tokens_[pos_]; }

  // The next token after carrying out any directives before it.
  // (A copy: a directive carried out later, an #include, may move the tokens.)
  Token peek() {
    while (tokens_[pos_].kind == TokenKind::Directive) directive();
    const Token& t = tokens_[pos_];
    if (t.kind == TokenKind::Identifier && !unusable_.empty())
      if (const auto it = unusable_.find(t.text); it != unusable_.end())
        throw Unusable(loc(t), "'" + t.text + "' cannot be used: its declaration holds what strahl's POV-Ray importer does "
                                              "not read (" + it->second + ")");
    return t;
  }
  // The error of using such a name (a declaration that uses one is unusable too).
  struct Unusable : Error {
    using Error::Error;
  };

  // A name right after a directive (#declare NAME, #ifdef (NAME) …): read as it stands.
  Token name_after_directive(const char* what) {
    const Token t = tokens_[pos_];
    if (t.kind != TokenKind::Identifier) throw Error(loc(t), std::string("expected a name ") + what + ", found " + describe(t));
    ++pos_;
    return t;
  }
  Token next() {
    Token t = peek();
    if (t.kind != TokenKind::End) ++pos_;
    return t;
  }
  bool is_symbol(const Token& t, const char* s) const { return t.kind == TokenKind::Symbol && t.text == s; }
  bool is_word(const Token& t, const char* s) const { return t.kind == TokenKind::Identifier && t.text == s; }
  bool accept_symbol(const char* s) {
    if (!is_symbol(peek(), s)) return false;
    ++pos_;
    return true;
  }
  bool accept_raw_symbol(const char* s) {  // without carrying out directives (an expression's end)
    if (!is_symbol(raw(), s)) return false;
    ++pos_;
    return true;
  }
  void expect_symbol(const char* s, const char* where) {
    const Token t = next();
    if (!is_symbol(t, s)) throw Error(loc(t), std::string("expected '") + s + "' " + where + ", found " + describe(t));
  }
  static std::string describe(const Token& t) {
    switch (t.kind) {
      case TokenKind::Number: return "the number " + yaml_number(t.number);
      case TokenKind::String: return "a string";
      case TokenKind::Identifier: return "'" + t.text + "'";
      case TokenKind::Directive: return "#" + t.text;
      case TokenKind::Symbol: return "'" + t.text + "'";
      case TokenKind::End: return "the end of the file";
    }
    return "?";
  }
  [[noreturn]] void unsupported(const Token& t, const std::string& where) {
    if (t.kind == TokenKind::End) throw Error(loc(t), "the file ends inside " + where + " (a '}' is missing)");
    throw Error(loc(t), "'" + t.text + "'" + (where.empty() ? "" : " in " + where) +
                           " is not supported by strahl's POV-Ray importer (docs/pov-import.md)");
  }
  // A texture's note (Texture::notes) while one is being read, else a warning.
  void note(const FileLoc& where, const std::string& message) {
    if (!noting_) return warn(where, message);
    const std::string n = where.str() + ": " + message;
    if (std::find(noting_->notes.begin(), noting_->notes.end(), n) == noting_->notes.end()) noting_->notes.push_back(n);
  }
  struct Noting {
    Noting(Reader& r, Texture& t) : reader(r), saved(r.noting_) { r.noting_ = &t; }
    ~Noting() { reader.noting_ = saved; }
    Reader& reader;
    Texture* saved;
  };

  void warn(const FileLoc& loc, const std::string& message) {
    const std::string w = loc.str() + ": " + message;
    if (warned_.insert(message).second) out_.warnings.push_back(w);
  }

  struct Control {
    std::string name;      // if, while, for, macro
    std::size_t loop = 0;  // while: the #while token; for: the first token of the body; macro: where it returns
    std::string var;       // for: its variable; macro: its name
    double end = 0, step = 1;
    FileLoc loc;
    // macro: the names its parameters and #local hide, with what they were (none: undeclared).
    std::vector<std::pair<std::string, std::optional<Value>>> hidden = {};
  };

  struct Macro {
    std::vector<std::string> params;
    std::size_t body = 0;  // the first token after its parameter list
  };

  void directive() {
    const std::size_t at = pos_;
    const Token d = tokens_[pos_++];
    const std::string& n = d.text;
    if (n == "declare" || n == "local") {
      Token name = name_after_directive(("after #" + n).c_str());
      if (name.text == "deprecated") {  // #declare deprecated [once] "message" NAME = …
        if (is_word(tokens_[pos_], "once")) ++pos_;
        if (tokens_[pos_].kind == TokenKind::String) ++pos_;
        name = name_after_directive("after #declare deprecated");
      }
      expect_symbol("=", ("after #" + n + " " + name.text).c_str());
      if (n == "local") hide_in_macro(name.text);
      declare(name);
    } else if (n == "macro") {
      const Token name = next();
      if (name.kind != TokenKind::Identifier) throw Error(loc(name), "expected a name after #macro, found " + describe(name));
      expect_symbol("(", "after the macro's name");
      Macro m;
      // Names separated by commas (POV-Ray also reads them without, and with one after the last).
      while (!accept_symbol(")")) {
        const Token p = next();
        if (p.kind != TokenKind::Identifier) throw Error(loc(p), "expected a parameter name or ')', found " + describe(p));
        m.params.push_back(p.text);
        accept_symbol(",");
      }
      m.body = pos_;
      macros_[name.text] = std::move(m);
      skip_to_end(d);
    } else if (n == "undef") {
      const Token name = name_after_directive("after #undef");
      symbols_.erase(name.text);
      unusable_.erase(name.text);
    } else if (n == "version") {
      version_ = expression().f();
      accept_raw_symbol(";");
    } else if (n == "include") {
      Token file = peek();
      file.text = string_value();
      include(file, at);
    } else if (n == "if" || n == "ifdef" || n == "ifndef") {
      bool taken;
      if (n == "if") {
        taken = condition(d);
      } else {
        expect_symbol("(", ("after #" + n).c_str());
        const Token name = name_after_directive(("in #" + n).c_str());
        expect_symbol(")", ("after #" + n + " (" + name.text).c_str());
        taken = symbols_.count(name.text) > 0 || unusable_.count(name.text) > 0;
        if (n == "ifndef") taken = !taken;
      }
      if (taken) {
        controls_.push_back(Control{"if", 0, {}, 0, 1, loc(d)});
      } else {
        skip_to_else(d);
      }
    } else if (n == "switch") {
      switch_directive(d);
    } else if ((n == "case" || n == "range" || n == "else") && !controls_.empty() && controls_.back().name == "switch") {
      if (n != "else") case_holds(d, 0);  // falling through: read past its value
    } else if (n == "break") {
      // Out of the innermost #switch, and out of the #if, #while and #for inside it.
      std::size_t open = 0;
      while (open < controls_.size() && controls_[controls_.size() - 1 - open].name != "switch") {
        if (controls_[controls_.size() - 1 - open].name == "macro") open = controls_.size();
        else ++open;
      }
      if (open == controls_.size()) throw Error(loc(d), "#break outside a #switch");
      for (std::size_t i = 0; i <= open; ++i) {
        controls_.pop_back();
        skip_to_end(d);
      }
    } else if (n == "else" || n == "elseif") {
      if (controls_.empty() || controls_.back().name != "if") throw Error(loc(d), "#" + n + " without #if");
      controls_.pop_back();
      skip_to_end(d);  // the branch taken has ended
    } else if (n == "while") {
      if (condition(d)) {
        controls_.push_back(Control{"while", at, {}, 0, 1, loc(d)});
      } else {
        skip_to_end(d);
      }
    } else if (n == "for") {
      expect_symbol("(", "after #for");
      const Token var = next();
      if (var.kind != TokenKind::Identifier) throw Error(loc(var), "#for needs a variable name");
      expect_symbol(",", "after #for's variable");
      const double start = expression().f();
      expect_symbol(",", "after #for's start");
      const double end = expression().f();
      double step = 1;
      if (accept_symbol(",")) step = expression().f();
      expect_symbol(")", "after #for's range");
      if (step == 0 || !std::isfinite(step)) throw Error(loc(d), "#for's step must not be 0");
      symbols_[var.text] = Value{Value::Kind::Number, number(start), {}, {}, {}};
      if (step > 0 ? start <= end : start >= end) {
        controls_.push_back(Control{"for", pos_, var.text, end, step, loc(d)});
      } else {
        skip_to_end(d);
      }
    } else if (n == "end") {
      if (controls_.empty()) throw Error(loc(d), "#end without #if, #while, #for, #switch or #macro");
      Control& c = controls_.back();
      count_iteration(c.loc);
      if (c.name == "macro") {
        pos_ = c.loop;
        unwind_to(controls_.size() - 1);
      } else if (c.name == "while") {
        pos_ = c.loop;
        controls_.pop_back();
      } else if (c.name == "for") {
        const double v = symbol_number(c.var, loc(d)) + c.step;
        symbols_[c.var] = Value{Value::Kind::Number, number(v), {}, {}, {}};
        if (c.step > 0 ? v <= c.end : v >= c.end) {
          pos_ = c.loop;
        } else {
          controls_.pop_back();
        }
      } else {
        controls_.pop_back();
      }
    } else if (n == "debug" || n == "warning") {
      const std::string text = string_value();
      if (n == "warning") warn(loc(d), "#warning: " + text);
    } else if (n == "error") {
      throw Error(loc(d), "#error: " + string_value());
    } else if (n == "default") {
      expect_symbol("{", "after #default");
      while (!accept_symbol("}")) {
        const Token t = next();
        if (!texture_item(t, out_.default_texture)) unsupported(t, "#default");
      }
    } else {
      throw Error(loc(d), "#" + n + " is not supported by strahl's POV-Ray importer (docs/pov-import.md)");
    }
  }

  void count_iteration(const FileLoc& loc) {
    if (++iterations_ > options_.max_loop_iterations)
      throw Error(loc, "more than " + std::to_string(options_.max_loop_iterations) + " loop iterations (an endless #while?)");
  }

  bool condition(const Token& d) {
    const Num c = expression();
    if (c.dim != 1) throw Error(loc(d), "#" + d.text + " needs a float condition, not a vector");
    return c.f() != 0;
  }

  // Skips a branch not taken: to the matching #else (then reads on), a true #elseif, or #end.
  void skip_to_else(const Token& d) {
    for (;;) {
      const Token t = skip_to_directive(d, Stop::Else);
      if (t.text == "end") return;
      if (t.text == "else") {
        controls_.push_back(Control{"if", 0, {}, 0, 1, loc(d)});
        return;
      }
      // #elseif (condition)
      if (condition(t)) {
        controls_.push_back(Control{"if", 0, {}, 0, 1, loc(d)});
        return;
      }
    }
  }
  void skip_to_end(const Token& d) {
    while (skip_to_directive(d, Stop::End).text != "end") {
    }
  }

  // #switch (value): on at the first #case (v) with v = value, #range (lo, hi) holding it, or
  // #else; then through the clauses after it (POV-Ray's fall-through) to #break or #end.
  void switch_directive(const Token& d) {
    const double value = expression().f();
    for (;;) {
      const Token t = skip_to_directive(d, Stop::Case);
      if (t.text == "end") return;
      if (t.text == "else" || case_holds(t, value)) {
        controls_.push_back(Control{"switch", 0, {}, 0, 1, loc(d)});
        return;
      }
    }
  }
  bool case_holds(const Token& t, double value) {
    expect_symbol("(", ("after #" + t.text).c_str());
    const double a = expression().f();
    if (t.text == "case") {
      expect_symbol(")", "after #case's value");
      return value == a;
    }
    expect_symbol(",", "between #range's bounds");
    const double b = expression().f();
    expect_symbol(")", "after #range's bounds");
    return a <= value && value <= b;
  }

  // Where skip_to_directive stops at this level, besides #end.
  enum class Stop { End, Else, Case };  // Else: #else, #elseif; Case: #case, #range, #else

  // Moves past the next #end (or the directives `stop` names) at this level.
  Token skip_to_directive(const Token& d, Stop stop) {
    int depth = 0;
    for (;;) {
      const Token& t = tokens_[pos_];
      if (t.kind == TokenKind::End) throw Error(loc(d), "this #" + d.text + " has no #end");
      ++pos_;
      if (t.kind != TokenKind::Directive) continue;
      if (t.text == "if" || t.text == "ifdef" || t.text == "ifndef" || t.text == "while" || t.text == "for" ||
          t.text == "switch" || t.text == "macro") {
        ++depth;
      } else if (t.text == "end") {
        if (depth == 0) return t;
        --depth;
      } else if (depth == 0 && stop == Stop::Else && (t.text == "else" || t.text == "elseif")) {
        return t;
      } else if (depth == 0 && stop == Stop::Case && (t.text == "case" || t.text == "range" || t.text == "else")) {
        return t;
      }
    }
  }

  // #declare NAME = value. A declared item (a pigment, finish, texture, object, function … in
  // braces) that holds what the importer does not read makes NAME unusable, not the file: include
  // files such as textures.inc declare many, and a scene uses few. Using it is the error.
  void declare(const Token& name) {
    while (tokens_[pos_].kind == TokenKind::Directive) directive();
    const Token first = tokens_[pos_];  // (as it stands: an unusable name is caught below)
    const bool item = first.kind == TokenKind::Identifier && pos_ + 1 < tokens_.size() &&
                      (is_symbol(tokens_[pos_ + 1], "{") || (first.text == "function" && is_symbol(tokens_[pos_ + 1], "(")));
    const std::size_t start = pos_, depth = controls_.size();
    const int in_vector = in_vector_;
    try {
      Value v = value();
      accept_raw_symbol(";");
      symbols_[name.text] = std::move(v);
      unusable_.erase(name.text);
    } catch (const Error& e) {
      const bool uses_unusable = dynamic_cast<const Unusable*>(&e) != nullptr;
      if (!item && !uses_unusable) throw;
      in_vector_ = in_vector;
      unwind_to(depth);
      pos_ = start;
      if (item) {
        ++pos_;
        if (is_symbol(tokens_[pos_], "(")) skip_balanced("(", ")");
        skip_balanced("{", "}");
        skip_layers();
        accept_raw_symbol(";");
      } else if (!skip_to_semicolon()) {
        throw;
      }
      symbols_.erase(name.text);
      unusable_[name.text] = e.what();
    }
  }
  // Past the ';' that ends a declaration, if one does (before the next directive).
  bool skip_to_semicolon() {
    for (int level = 0;;) {
      const Token& t = tokens_[pos_];
      if (t.kind == TokenKind::End || t.kind == TokenKind::Directive) return false;
      ++pos_;
      if (is_symbol(t, "(") || is_symbol(t, "{") || is_symbol(t, "<")) ++level;
      if (is_symbol(t, ")") || is_symbol(t, "}") || is_symbol(t, ">")) --level;
      if (level <= 0 && is_symbol(t, ";")) return true;
    }
  }
  // Closes the frames opened since `depth` (a declaration given up): macros give back what they hid.
  void unwind_to(std::size_t depth) {
    while (controls_.size() > depth) {
      Control& c = controls_.back();
      for (auto it = c.hidden.rbegin(); it != c.hidden.rend(); ++it) {
        if (it->second) symbols_[it->first] = std::move(*it->second);
        else symbols_.erase(it->first);
      }
      controls_.pop_back();
    }
  }
  // A layered texture's further layers (texture { … } texture { … }): read past. Returns whether
  // there were any.
  bool skip_layers() {
    bool any = false;
    while (is_word(tokens_[pos_], "texture") && pos_ + 1 < tokens_.size() && is_symbol(tokens_[pos_ + 1], "{")) {
      ++pos_;
      skip_balanced("{", "}");
      any = true;
    }
    return any;
  }

  // From an opening bracket to its partner, reading nothing.
  void skip_balanced(const char* open, const char* close) {
    const Token start = tokens_[pos_];
    if (!is_symbol(start, open)) throw Error(loc(start), std::string("expected '") + open + "'");
    for (int level = 0;;) {
      const Token& t = tokens_[pos_];
      if (t.kind == TokenKind::End) throw Error(loc(start), std::string("this '") + open + "' is never closed");
      ++pos_;
      if (is_symbol(t, open)) ++level;
      if (is_symbol(t, close) && --level == 0) return;
    }
  }

  // A macro's parameter or #local name: what it was is given back when the macro returns.
  void hide_in_macro(const std::string& name) {
    for (auto c = controls_.rbegin(); c != controls_.rend(); ++c) {
      if (c->name != "macro") continue;
      for (const auto& h : c->hidden)
        if (h.first == name) return;
      const auto it = symbols_.find(name);
      c->hidden.emplace_back(name, it == symbols_.end() ? std::nullopt : std::optional<Value>(it->second));
      return;
    }
  }

  bool is_macro(const Token& t) const { return t.kind == TokenKind::Identifier && macros_.count(t.text) > 0; }

  // NAME(arguments): the arguments are evaluated, the parameters declared (hiding what they
  // named) and reading goes on in the body until its #end, which returns here.
  void call_macro(const Token& name) {
    const Macro& m = macros_.at(name.text);
    expect_symbol("(", ("after the macro " + name.text).c_str());
    std::vector<Value> args;
    if (!accept_symbol(")")) {
      do args.push_back(value());
      while (accept_symbol(","));
      expect_symbol(")", ("to close " + name.text + "(").c_str());
    }
    if (args.size() != m.params.size())
      throw Error(loc(name), "the macro " + name.text + " takes " + std::to_string(m.params.size()) + " arguments, not " +
                                 std::to_string(args.size()));
    if (std::count_if(controls_.begin(), controls_.end(), [](const Control& c) { return c.name == "macro"; }) >= kMaxNesting)
      throw Error(loc(name), "macros called more than " + std::to_string(kMaxNesting) + " deep");
    count_iteration(loc(name));
    controls_.push_back(Control{"macro", pos_, name.text, 0, 1, loc(name)});
    for (std::size_t i = 0; i < args.size(); ++i) {
      hide_in_macro(m.params[i]);
      symbols_[m.params[i]] = std::move(args[i]);
    }
    pos_ = m.body;
  }

  // After a value read from a macro's body: its #end (and any directives before it) must follow.
  void finish_macro(std::size_t depth, const Token& name) {
    while (controls_.size() > depth) {
      if (raw().kind != TokenKind::Directive)
        throw Error(loc(raw()), "the macro " + name.text + " gives more than one value here (expected its #end)");
      directive();
    }
  }

  void include(const Token& file, std::size_t at) {
    if (++includes_ > kMaxIncludes) throw Error(loc(file), "more than " + std::to_string(kMaxIncludes) + " #include (an include loop?)");
    fs::path p = fs::path(loc(file).file).parent_path() / file.text;
    std::error_code ec;
    if (!fs::exists(p, ec)) {
      for (const char* dir : {"/usr/share/povray-3.7/include", "/usr/local/share/povray-3.7/include"})
        if (fs::exists(fs::path(dir) / file.text, ec)) p = fs::path(dir) / file.text;
    }
    if (!fs::exists(p, ec)) throw Error(loc(file), "#include \"" + file.text + "\": no such file beside the scene (nor in POV-Ray's include directory)");
    std::vector<Token> more = read_tokens(p, loc(file));
    more.pop_back();  // its End
    if (tokens_.size() + more.size() > kMaxTokens)
      throw Error(loc(file), "the scene and its includes hold more than " + std::to_string(kMaxTokens) + " tokens");
    // The directive is replaced by the file's tokens (a loop that comes back here reads them,
    // not the directive again); positions kept past it move with them.
    const std::ptrdiff_t delta = std::ptrdiff_t(more.size()) - std::ptrdiff_t(pos_ - at);
    tokens_.erase(tokens_.begin() + std::ptrdiff_t(at), tokens_.begin() + std::ptrdiff_t(pos_));
    tokens_.insert(tokens_.begin() + std::ptrdiff_t(at), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
    pos_ = at;
    for (Control& c : controls_)
      if (c.loop > at) c.loop = std::size_t(std::ptrdiff_t(c.loop) + delta);
    for (auto& [name, m] : macros_)
      if (m.body > at) m.body = std::size_t(std::ptrdiff_t(m.body) + delta);
  }

  // ---- expressions --------------------------------------------------------------------------

  Value value() {
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
      if (kShapes.count(t.text)) {
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

  double symbol_number(const std::string& name, const FileLoc& loc) {
    const auto it = symbols_.find(name);
    if (it == symbols_.end() || it->second.kind != Value::Kind::Number) throw Error(loc, "'" + name + "' is not a float");
    return it->second.num.f();
  }

  // Nesting (parentheses, unary signs, objects in objects) is bounded: no stack overflow.
  struct Nesting {
    Nesting(Reader& r, const Token& t) : reader(r) {
      if (++reader.nesting_ > kMaxNesting) throw Error(r.loc(t), "nested more than " + std::to_string(kMaxNesting) + " deep");
    }
    ~Nesting() { --reader.nesting_; }
    Reader& reader;
  };

  Num expression() {
    const Nesting n(*this, raw());
    return conditional();
  }

  Num conditional() {
    Num c = logical_or();
    if (accept_raw_symbol("?")) {
      const Num a = conditional();
      expect_symbol(":", "in a ? : expression");
      const Num b = conditional();
      return c.f() != 0 ? a : b;
    }
    return c;
  }
  Num logical_or() {
    Num a = logical_and();
    while (accept_raw_symbol("|")) a = number(a.f() != 0 || logical_and().f() != 0);
    return a;
  }
  Num logical_and() {
    Num a = comparison();
    while (accept_raw_symbol("&")) a = number((comparison().f() != 0) && a.f() != 0);
    return a;
  }
  Num comparison() {
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
  Num sum() {
    Num a = product();
    for (;;) {
      if (accept_raw_symbol("+")) a = combine(a, product(), [](double x, double y) { return x + y; });
      else if (accept_raw_symbol("-")) a = combine(a, product(), [](double x, double y) { return x - y; });
      else return a;
    }
  }
  Num product() {
    Num a = unary();
    for (;;) {
      if (accept_raw_symbol("*")) a = combine(a, unary(), [](double x, double y) { return x * y; });
      else if (accept_raw_symbol("/")) a = combine(a, unary(), [](double x, double y) { return x / y; });
      else return a;
    }
  }
  static Num combine(const Num& a, const Num& b, const std::function<double(double, double)>& f) {
    Num r;
    r.dim = std::max(a.dim, b.dim);
    for (int i = 0; i < r.dim; ++i) r.c[std::size_t(i)] = f(a.dim == 1 ? a.c[0] : a.c[std::size_t(i)], b.dim == 1 ? b.c[0] : b.c[std::size_t(i)]);
    return r;
  }
  Num unary() {
    const Nesting n(*this, raw());
    if (accept_symbol("-")) return combine(number(0), unary(), [](double, double y) { return -y; });
    if (accept_symbol("+")) return unary();
    if (accept_symbol("!")) return number(unary().f() == 0);
    return postfix(primary());
  }
  Num postfix(Num v) {
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

  Num primary() {
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

  Num function(const Token& t) {
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

  // A count from a float, clamped to [lo, hi] before it becomes an int (NaN: lo).
  static int whole(double v, int lo, int hi) { return v >= lo ? (v <= hi ? int(v) : hi) : lo; }

  // Whether `t` begins a float (an optional value such as metallic's).
  bool starts_value(const Token& t) const {
    if (t.kind == TokenKind::Number) return true;
    if (t.kind == TokenKind::Symbol) return t.text == "(" || t.text == "-" || t.text == "+" || t.text == "!";
    if (t.kind != TokenKind::Identifier) return false;
    const auto it = symbols_.find(t.text);
    return (it != symbols_.end() && it->second.kind == Value::Kind::Number) || is_macro(t) || t.text == "pi";
  }

  // A string: "text", a declared string, concat(…), str(float, width, digits), chr(code).
  std::string string_value() {
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

  Vector vector() { return to_vector(expression()); }
  double real() { return expression().f(); }

  // `color`/`colour` (optional) then rgb, rgbf, rgbt, rgbft and red/green/blue/filter/transmit,
  // or any colour expression.
  Color color() {
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

  // ---- statements and items -------------------------------------------------------------------

  void statement() {
    const Token t = next();
    if (t.kind == TokenKind::Symbol && t.text == ";") return;
    if (t.kind != TokenKind::Identifier) throw Error(loc(t), "expected an object, light or camera, found " + describe(t));
    const std::string& n = t.text;
    if (n == "camera") return camera(t);
    if (n == "light_source") return out_.lights.push_back(light(t));
    if (n == "global_settings") return global_settings();
    if (n == "background") {
      expect_symbol("{", "after background");
      out_.background = color();
      expect_symbol("}", "to close background");
      return;
    }
    if (kShapes.count(n)) {
      Object o = object(t);
      add_top_level(std::move(o), {}, nullptr);
      return;
    }
    if (is_macro(t)) return call_macro(t);  // (its body's items follow)
    if (n == "sky_sphere" || n == "fog" || n == "media" || n == "rainbow" || n == "photons" || n == "radiosity")
      unsupported(t, "");
    if (const auto it = symbols_.find(n); it != symbols_.end()) {
      if (it->second.kind == Value::Kind::Object) throw Error(loc(t), "use a declared object as object { " + n + " }");
    }
    throw Error(loc(t), "unknown item '" + n + "' (an object, light_source, camera, global_settings or background)");
  }

  // A union at the top level is a group: its parts become objects of the scene, each with the
  // union's transforms after its own and the union's texture where it has none (POV-Ray's rules).
  void add_top_level(Object o, const std::vector<std::string>& outer_steps, const Texture* outer_texture) {
    if (!o.texture.given() && outer_texture) o.texture = *outer_texture;
    o.steps.insert(o.steps.end(), outer_steps.begin(), outer_steps.end());
    if (o.type == "union" && !o.inverse) {
      std::vector<Object> parts = std::move(o.children);
      for (Object& p : parts) add_top_level(std::move(p), o.steps, o.texture.given() ? &o.texture : nullptr);
      return;
    }
    if (out_.objects.size() >= options_.max_objects)
      throw Error(o.loc, "more than " + std::to_string(options_.max_objects) + " objects (the importer's limit)");
    out_.objects.push_back(std::move(o));
  }

  void camera(const Token& kw) {
    Camera& c = out_.camera;
    c.loc = loc(kw);
    expect_symbol("{", "after camera");
    while (!accept_symbol("}")) {
      const Token t = next();
      const std::string& n = t.text;
      if (n == "perspective") continue;
      if (n == "location") c.location = vector();
      else if (n == "look_at") c.look_at = vector(), c.has_look_at = true;
      else if (n == "right") c.right = vector();
      else if (n == "up") c.up = vector();
      else if (n == "direction") c.direction = vector();
      else if (n == "sky") c.sky = vector();
      else if (n == "angle") c.angle = real(), c.has_angle = true;
      else if (n == "aperture") c.aperture = real();
      else if (n == "focal_point") c.focal_point = vector(), c.has_focal_point = true;
      else if (n == "blur_samples") {
        c.blur_samples = whole(real(), 1, 1 << 20);
        if (accept_symbol(",")) c.blur_samples = whole(real(), 1, 1 << 20);
      } else if (n == "confidence" || n == "variance") real();
      else unsupported(t, "camera");
    }
  }

  Light light(const Token& kw) {
    Light l;
    l.loc = loc(kw);
    expect_symbol("{", "after light_source");
    l.position = vector();
    while (!accept_symbol("}")) {
      const Token t = next();
      const std::string& n = t.text;
      if (is_symbol(t, ",")) continue;
      if (n == "color" || n == "colour" || n.rfind("rgb", 0) == 0 || starts_value(t)) {
        --pos_;
        l.color = color();
      } else if (n == "area_light") {
        vector(), accept_symbol(","), vector(), accept_symbol(","), real(), accept_symbol(","), real();
        warn(loc(t), "area_light is drawn as a point light (strahl's area lights are rect, disk and sphere emitters)");
      } else if (n == "parallel") {
        l.parallel = true;
      } else if (n == "point_at") {
        l.point_at = vector();
      } else if (n == "fade_distance" || n == "fade_power") {
        real();
        warn(loc(t), n + " is left out: strahl's point lights do not fall off with distance");
      } else if (n == "shadowless") {
        warn(loc(t), "shadowless is left out: the light casts shadows");
      } else if (n == "adaptive" || n == "jitter" || n == "circular" || n == "orient") {
        if (n == "adaptive") real();
      } else {
        unsupported(t, "light_source");
      }
    }
    return l;
  }

  void global_settings() {
    expect_symbol("{", "after global_settings");
    while (!accept_symbol("}")) {
      const Token t = next();
      const std::string& n = t.text;
      if (n == "assumed_gamma") {
        gamma_given_ = true;
        const double g = real();
        if (g != 1) warn(loc(t), "assumed_gamma " + yaml_number(g) + " is ignored: strahl's colours are linear (assumed_gamma 1)");
      } else if (n == "max_trace_level") {
        out_.max_trace_level = whole(real(), -1, 1000);
      } else if (n == "ambient_light") {
        out_.ambient_light = color();
      } else if (n == "adc_bailout" || n == "number_of_waves" || n == "noise_generator" || n == "charset" ||
                 n == "irid_wavelength" || n == "max_intersections") {
        if (n == "charset") next();
        else if (n == "irid_wavelength") color();
        else real();
      } else {
        unsupported(t, "global_settings");
      }
    }
  }

  // A texture's parts: pigment, finish, interior, texture and the bump map `normal` (left out).
  bool texture_item(const Token& t, Texture& tex) {
    const Noting noting(*this, tex);
    const std::string& n = t.text;
    if (n == "pigment" || n == "finish" || n == "interior" || n == "texture") {
      texture_block(n, tex);
      return true;
    }
    if (n == "normal") {
      note(loc(t), "normal (bump maps) is left out");
      skip_block();
      return true;
    }
    return false;
  }

  void skip_block() {
    expect_symbol("{", "");
    for (int depth = 1; depth > 0;) {
      const Token t = next();
      if (t.kind == TokenKind::End) throw Error(loc(t), "a block is never closed (no })");
      if (is_symbol(t, "{")) ++depth;
      if (is_symbol(t, "}")) --depth;
    }
  }

  // pigment { … }, finish { … }, interior { … } or texture { … }, starting from a declared one
  // of the same kind if the block begins with its name.
  void texture_block(const std::string& kind, Texture& tex) {
    const Noting noting(*this, tex);
    expect_symbol("{", ("after " + kind).c_str());
    const Token& first = peek();
    if (first.kind == TokenKind::Identifier) {
      const auto it = symbols_.find(first.text);
      const bool texture_value = it != symbols_.end() &&
                                 (it->second.kind == Value::Kind::Pigment || it->second.kind == Value::Kind::Finish ||
                                  it->second.kind == Value::Kind::Interior || it->second.kind == Value::Kind::Texture);
      if (it != symbols_.end() && !texture_value && it->second.kind != Value::Kind::Number)
        throw Error(loc(first), "'" + first.text + "' is not a pigment, finish, interior or texture");
      if (texture_value) {
        const Texture& d = it->second.texture;
        next();
        tex.notes.insert(tex.notes.end(), d.notes.begin(), d.notes.end());
        if (kind == "texture" || kind == "pigment") tex.pigment = d.pigment, tex.has_pigment |= d.has_pigment;
        if (kind == "texture" || kind == "finish") tex.finish = d.finish, tex.has_finish |= d.has_finish;
        if (kind == "texture" || kind == "interior") tex.interior = d.interior, tex.has_interior |= d.has_interior;
      }
    }
    if (kind == "pigment") tex.has_pigment = true;
    if (kind == "finish") tex.has_finish = true;
    if (kind == "interior") tex.has_interior = true;
    while (!accept_symbol("}")) {
      const Token t = peek();
      if (kind == "texture") {
        next();
        if (!texture_item(t, tex)) {
          if (t.text == "scale" || t.text == "translate" || t.text == "rotate") vector();
          else unsupported(t, "texture");
        }
      } else if (kind == "pigment") {
        pigment_item(tex.pigment);
      } else if (kind == "finish") {
        finish_item(tex.finish);
      } else {
        interior_item(tex.interior);
      }
    }
  }

  void pigment_item(Pigment& p) {
    const Token t = peek();
    const std::string& n = t.text;
    if (n == "checker") {
      next();
      p.checker = true;
      p.color = color();
      accept_symbol(",");
      p.color2 = color();
    } else if (n == "scale") {
      next();
      const Num s = expression();
      if (s.dim != 1 && !(s.c[0] == s.c[1] && s.c[1] == s.c[2])) note(loc(t), "a pigment's uneven scale is left out");
      p.scale *= s.c[0];
    } else if (n == "translate" || n == "rotate") {
      next();
      vector();
      note(loc(t), "a pigment's translate and rotate are left out");
    } else if (n == "quick_color" || n == "quick_colour") {
      next();
      color();
    } else if (t.kind == TokenKind::Identifier && (n == "color" || n == "colour" || n.rfind("rgb", 0) == 0 || symbols_.count(n) ||
                                                   n == "red" || n == "green" || n == "blue" || n == "filter" || n == "transmit")) {
      p.color = color();
    } else if (t.kind == TokenKind::Identifier) {
      next();
      unsupported(t, "pigment");
    } else {
      p.color = color();
    }
  }

  Color finish_color() {
    const Token& t = peek();
    if (t.kind == TokenKind::Number || is_symbol(t, "(") || is_symbol(t, "-")) return to_color(expression());
    return color();
  }
  double grey(const Color& c, const FileLoc& loc, const std::string& what) {
    if (c[0] == c[1] && c[1] == c[2]) return c[0];
    note(loc, "a coloured " + what + " is drawn grey (its mean): strahl's " + what + " is one number");
    return (c[0] + c[1] + c[2]) / 3;
  }

  void finish_item(Finish& f) {
    const Token t = next();
    const std::string& n = t.text;
    if (n == "ambient") f.ambient = grey(finish_color(), loc(t), "ambient");
    else if (n == "diffuse") f.diffuse = real();
    else if (n == "specular") f.specular = real();
    else if (n == "roughness") f.roughness = real();
    else if (n == "phong") {
      f.phong = real();
      note(loc(t), "phong is drawn as a Blinn-Phong highlight (specular phong, shininess 4 × phong_size)");
    } else if (n == "phong_size") f.phong_size = real();
    else if (n == "reflection") {
      if (accept_symbol("{")) {
        Color c = finish_color();
        if (accept_symbol(",")) c = finish_color();  // reflection { min, max }: the max
        while (!accept_symbol("}")) {
          const Token r = next();
          if (r.text == "fresnel") f.fresnel = real() != 0;
          else if (r.text == "falloff" || r.text == "exponent") real();
          else if (r.text == "metallic") {
            if (!is_symbol(peek(), "}") && peek().kind == TokenKind::Number) real();
          } else unsupported(r, "reflection");
        }
        f.reflection = grey(c, loc(t), "reflection");
      } else {
        f.reflection = grey(finish_color(), loc(t), "reflection");
      }
    } else if (n == "brilliance" || n == "metallic" || n == "crand" || n == "emission") {
      if (n == "emission") finish_color();
      else if (n != "metallic" || starts_value(peek())) real();
      note(loc(t), n + " is left out");
    } else if (n == "conserve_energy") {
    } else {
      unsupported(t, "finish");
    }
  }

  void interior_item(Interior& in) {
    const Token t = next();
    const std::string& n = t.text;
    if (n == "ior") in.ior = real();
    else if (n == "fresnel") in.fresnel = real() != 0;
    else if (n == "caustics" || n == "dispersion" || n == "fade_distance" || n == "fade_power") {
      real();
      note(loc(t), n + " is left out");
    } else if (n == "dispersion_samples") real();
    else unsupported(t, "interior");
  }

  // ---- objects -------------------------------------------------------------------------------

  Object object(const Token& kw) {
    const Nesting nest(*this, kw);
    Object o;
    o.loc = loc(kw);
    expect_symbol("{", ("after " + kw.text).c_str());
    const std::string& n = kw.text;
    if (n == "object") {
      const Token t = next();
      if (kShapes.count(t.text)) {
        o = object(t);
      } else {
        const auto it = symbols_.find(t.text);
        if (t.kind != TokenKind::Identifier || it == symbols_.end() || it->second.kind != Value::Kind::Object)
          throw Error(loc(t), "object { … } needs a declared object or a shape, found " + describe(t));
        o = *it->second.object;
      }
      o.loc = loc(kw);
    } else if (n == "sphere") {
      o.type = "sphere";
      const Vector c = vector();
      expect_symbol(",", "after the sphere's centre");
      o.keys = ", center: " + yaml_vector(c) + ", radius: " + yaml_number(real());
    } else if (n == "plane") {
      o.type = "plane";
      const Vector v = vector();
      expect_symbol(",", "after the plane's normal");
      const double d = real(), l = length(v);
      o.keys = ", normal: " + yaml_vector(l > 0 ? Vector{v[0] / l, v[1] / l, v[2] / l} : v) + ", distance: " + yaml_number(d);
    } else if (n == "box") {
      o.type = "box";
      const Vector a = vector();
      expect_symbol(",", "after the box's first corner");
      o.keys = ", corners: [" + yaml_vector(a) + ", " + yaml_vector(vector()) + "]";
    } else if (n == "cylinder" || n == "cone") {
      o.type = n;
      const Vector base = vector();
      expect_symbol(",", "after the base");
      std::string base_radius;
      if (n == "cone") {
        base_radius = yaml_number(real());
        expect_symbol(",", "after the base radius");
      }
      const Vector cap = vector();
      expect_symbol(",", "after the cap");
      const double r = real();
      o.keys = ", base: " + yaml_vector(base) + ", cap: " + yaml_vector(cap) +
               (n == "cone" ? ", base_radius: " + base_radius + ", cap_radius: " + yaml_number(r) : ", radius: " + yaml_number(r));
    } else if (n == "torus") {
      o.type = "torus";
      const double major = real();
      expect_symbol(",", "after the torus's major radius");
      o.keys = ", center: [0, 0, 0], major_radius: " + yaml_number(major) + ", minor_radius: " + yaml_number(real());
    } else if (n == "disc") {
      o.type = "disk";
      const Vector c = vector();
      expect_symbol(",", "after the disc's centre");
      const Vector nn = vector();
      expect_symbol(",", "after the disc's normal");
      o.keys = ", center: " + yaml_vector(c) + ", normal: " + yaml_vector(nn) + ", radius: " + yaml_number(real());
      if (accept_symbol(",") && real() != 0) throw Error(loc(kw), "a disc with a hole is not supported by strahl's POV-Ray importer");
    } else if (n == "triangle") {
      o.type = "triangle";
      const Vector a = vector();
      expect_symbol(",", "after a vertex");
      const Vector b = vector();
      expect_symbol(",", "after a vertex");
      o.keys = ", vertices: [" + yaml_vector(a) + ", " + yaml_vector(b) + ", " + yaml_vector(vector()) + "]";
    } else if (n == "quadric") {
      // quadric { <A, B, C>, <D, E, F>, <G, H, I>, J }: strahl's ten coefficients in this order.
      o.type = "quadric";
      std::string c;
      for (int i = 0; i < 3; ++i) {
        const Vector v = vector();
        expect_symbol(",", "after the quadric's coefficients");
        c += yaml_number(v[0]) + ", " + yaml_number(v[1]) + ", " + yaml_number(v[2]) + ", ";
      }
      o.keys = ", coefficients: [" + c + yaml_number(real()) + "]";
    } else if (n == "smooth_triangle" || n == "mesh" || n == "mesh2") {
      o = mesh(kw);
    } else if (n == "isosurface") {
      o = isosurface(kw);
    } else {  // union, intersection, difference, merge
      o.type = n;
      for (;;) {
        const Token t = peek();
        if (is_macro(t)) call_macro(next());  // (its objects are operands)
        else if (t.kind == TokenKind::Identifier && kShapes.count(t.text)) o.children.push_back(object(next()));
        else break;
      }
      if (o.children.empty()) throw Error(loc(kw), n + " needs at least one object");
    }
    modifiers(o, kw.text);
    return o;
  }

  // What follows a shape's own values: transforms, textures, flags, to the closing '}'.
  void modifiers(Object& o, const std::string& what) {
    while (!accept_symbol("}")) {
      const Token t = next();
      const std::string& n = t.text;
      if (t.kind == TokenKind::End) throw Error(o.loc, "this " + what + " is never closed (the file ends before its '}')");
      if (t.kind != TokenKind::Identifier) throw Error(loc(t), "expected a modifier of " + what + " or '}', found " + describe(t));
      if (n == "translate") o.steps.push_back("{translate: " + yaml_vector(vector()) + "}");
      else if (n == "rotate") o.steps.push_back("{rotate: " + yaml_vector(vector()) + "}");
      else if (n == "scale") o.steps.push_back("{scale: " + yaml_vector(vector()) + "}");
      else if (n == "matrix") o.steps.push_back(matrix_step());
      else if (n == "inverse") o.inverse = !o.inverse;
      else if (n == "open") {
        if (o.type != "cylinder" && o.type != "cone") unsupported(t, what);
        if (o.keys.find(", open: true") == std::string::npos) o.keys += ", open: true";
      } else if (n == "sturm" || n == "hollow" || n == "smooth") {
        if (n == "hollow" && starts_value(peek())) real();
      } else if (n == "no_shadow" || n == "no_reflection" || n == "no_image" || n == "double_illuminate") {
        warn(loc(t), n + " is left out");
      } else if (n == "clipped_by" && o.type == "quadric") {
        expect_symbol("{", "after clipped_by");
        const Token box = next();
        if (!is_word(box, "box")) throw Error(loc(box), "strahl clips a quadric by a box only, found " + describe(box));
        expect_symbol("{", "after box");
        const Vector a = vector();
        expect_symbol(",", "after the box's first corner");
        o.keys += ", clipped_by: {type: box, corners: [" + yaml_vector(a) + ", " + yaml_vector(vector()) + "]}";
        expect_symbol("}", "to close the box");
        expect_symbol("}", "to close clipped_by");
      } else if (n == "photons" || n == "bounded_by") {
        warn(loc(t), n + " { … } is left out");
        skip_block();
      } else if (n == "pigment" || n == "finish" || n == "interior" || n == "texture" || n == "normal") {
        if (!o.texture.given()) o.texture = out_.default_texture, o.texture.has_pigment = o.texture.has_finish = false;
        texture_item(t, o.texture);
      } else if (const auto it = symbols_.find(n); it != symbols_.end() && it->second.kind == Value::Kind::Texture) {
        o.texture = it->second.texture;
      } else {
        unsupported(t, what);
      }
    }
  }

  // matrix <a, b, c, d, e, f, g, h, i, j, k, l>: POV-Ray's rows act on row vectors,
  // p' = (x, y, z, 1) · M; strahl's matrix acts on columns: its rows are M's columns.
  std::string matrix_step() {
    expect_symbol("<", "after matrix");
    std::array<double, 12> m{};
    ++in_vector_;
    for (std::size_t i = 0; i < 12; ++i) {
      if (i > 0) expect_symbol(",", "between matrix entries");
      m[i] = real();
    }
    --in_vector_;
    expect_symbol(">", "to close the matrix (12 numbers)");
    std::string s = "{matrix: [";
    for (std::size_t r = 0; r < 3; ++r)
      s += std::string(r ? ", " : "") + "[" + yaml_number(m[r]) + ", " + yaml_number(m[3 + r]) + ", " + yaml_number(m[6 + r]) + ", " + yaml_number(m[9 + r]) + "]";
    return s + "]}";
  }

  Object mesh(const Token& kw) {
    Object o;
    o.type = "mesh";
    o.loc = loc(kw);
    MeshData data;
    auto add_triangle = [&](const Token& t, bool smooth) {
      std::array<Vector, 3> v{}, nn{};
      for (std::size_t i = 0; i < 3; ++i) {
        if (i > 0) expect_symbol(",", "between a triangle's vertices");
        v[i] = vector();
        if (smooth) {
          expect_symbol(",", "after a vertex");
          nn[i] = vector();
        }
      }
      (void)t;
      MeshData::Face f;
      for (std::size_t i = 0; i < 3; ++i) {
        f.v[i] = std::uint32_t(data.positions.size());
        data.positions.push_back(Vec3(v[i][0], v[i][1], v[i][2]));
        if (smooth) {
          f.n[i] = std::int32_t(data.normals.size());
          data.normals.push_back(Vec3(nn[i][0], nn[i][1], nn[i][2]));
        }
      }
      data.faces.push_back(f);
    };
    if (kw.text == "smooth_triangle") {
      add_triangle(kw, true);
    } else if (kw.text == "mesh") {
      while (is_word(peek(), "triangle") || is_word(peek(), "smooth_triangle")) {
        const Token t = next();
        expect_symbol("{", ("after " + t.text).c_str());
        add_triangle(t, t.text == "smooth_triangle");
        while (!accept_symbol("}")) {
          const Token x = next();
          if (x.text == "texture") {
            warn(loc(x), "a mesh triangle's own texture is left out");
            skip_block();
          } else unsupported(x, t.text);
        }
      }
    } else {
      mesh2(kw, data);
    }
    if (data.faces.empty()) throw Error(loc(kw), kw.text + " has no triangles");
    o.mesh = int(out_.meshes.size());
    out_.meshes.push_back(std::move(data));
    return o;
  }

  void mesh2(const Token& kw, MeshData& data) {
    std::vector<std::array<std::int64_t, 3>> normal_faces;
    auto count = [&](const char* what) {
      const double c = real();
      if (!(c >= 0 && c <= 1e8) || c != std::floor(c)) throw Error(loc(kw), std::string(what) + " needs a whole count");
      return std::size_t(c);
    };
    while (true) {
      const Token& t = peek();
      if (t.kind != TokenKind::Identifier) break;
      const std::string n = t.text;
      if (n == "vertex_vectors" || n == "normal_vectors") {
        next();
        expect_symbol("{", ("after " + n).c_str());
        const std::size_t k = count(n.c_str());
        for (std::size_t i = 0; i < k; ++i) {
          expect_symbol(",", ("in " + n).c_str());
          const Vector v = vector();
          (n == "vertex_vectors" ? data.positions : data.normals).push_back(Vec3(v[0], v[1], v[2]));
        }
        accept_symbol(",");
        expect_symbol("}", ("to close " + n + " (more entries than its count?)").c_str());
      } else if (n == "face_indices" || n == "normal_indices") {
        next();
        const FileLoc where = loc(t);
        expect_symbol("{", ("after " + n).c_str());
        const std::size_t k = count(n.c_str());
        for (std::size_t i = 0; i < k; ++i) {
          expect_symbol(",", ("in " + n).c_str());
          const Vector v = vector();
          std::array<std::int64_t, 3> f{};
          for (std::size_t j = 0; j < 3; ++j) {
            if (!(v[j] >= 0 && v[j] < 4e9) || v[j] != std::floor(v[j])) throw Error(where, n + ": an index is not a whole number ≥ 0");
            f[j] = std::int64_t(v[j]);
          }
          while (is_symbol(peek(), ",") && pos_ + 1 < tokens_.size() && tokens_[pos_ + 1].kind == TokenKind::Number) {
            next();
            next();  // texture indices: left out
          }
          if (n == "face_indices") {
            MeshData::Face face;
            for (std::size_t j = 0; j < 3; ++j) {
              if (std::size_t(f[j]) >= data.positions.size()) throw Error(where, "face_indices: index " + std::to_string(f[j]) + " is past the vertex_vectors");
              face.v[j] = std::uint32_t(f[j]);
            }
            data.faces.push_back(face);
          } else {
            normal_faces.push_back(f);
          }
        }
        accept_symbol(",");
        expect_symbol("}", ("to close " + n + " (more entries than its count?)").c_str());
      } else if (n == "uv_vectors" || n == "texture_list" || n == "uv_indices" || n == "inside_vector") {
        next();
        if (n == "inside_vector") vector();
        else skip_block();
      } else {
        break;
      }
    }
    if (!normal_faces.empty()) {
      if (normal_faces.size() != data.faces.size()) throw Error(loc(kw), "normal_indices needs one entry per face");
      for (std::size_t i = 0; i < normal_faces.size(); ++i)
        for (std::size_t j = 0; j < 3; ++j) {
          if (std::size_t(normal_faces[i][j]) >= data.normals.size()) throw Error(loc(kw), "normal_indices: an index is past the normal_vectors");
          data.faces[i].n[j] = std::int32_t(normal_faces[i][j]);
        }
    } else if (!data.normals.empty()) {
      if (data.normals.size() != data.positions.size()) throw Error(loc(kw), "normal_vectors needs one normal per vertex (or normal_indices)");
      for (MeshData::Face& f : data.faces)
        for (std::size_t j = 0; j < 3; ++j) f.n[j] = std::int32_t(f.v[j]);
    }
  }

  Object isosurface(const Token& kw) {
    Object o;
    o.type = "implicit";
    o.loc = loc(kw);
    std::string function, contained = "{type: box, corners: [[-1, -1, -1], [1, 1, 1]]}";
    double threshold = 0, max_gradient = 1.1, accuracy = 0.001;
    while (true) {
      const Token t = peek();
      if (t.kind != TokenKind::Identifier) break;
      const std::string n = t.text;
      if (n == "function") {
        next();
        function = function_text(t);
      } else if (n == "contained_by") {
        next();
        expect_symbol("{", "after contained_by");
        const Token s = next();
        expect_symbol("{", ("after " + s.text).c_str());
        const Vector a = vector();
        expect_symbol(",", ("in " + s.text).c_str());
        if (s.text == "sphere") contained = "{type: sphere, center: " + yaml_vector(a) + ", radius: " + yaml_number(real()) + "}";
        else if (s.text == "box") contained = "{type: box, corners: [" + yaml_vector(a) + ", " + yaml_vector(vector()) + "]}";
        else throw Error(loc(s), "contained_by needs a sphere or a box");
        expect_symbol("}", ("to close " + s.text).c_str());
        expect_symbol("}", "to close contained_by");
      } else if (n == "threshold") next(), threshold = real();
      else if (n == "max_gradient") next(), max_gradient = real();
      else if (n == "accuracy") next(), accuracy = real();
      else if (n == "open" || n == "evaluate" || n == "max_trace" || n == "all_intersections") {
        next();
        if (n == "evaluate") real(), expect_symbol(",", "in evaluate"), real(), expect_symbol(",", "in evaluate"), real();
        if (n == "max_trace") real();
        warn(loc(t), n + " is left out");
      } else {
        break;
      }
    }
    if (function.empty()) throw Error(loc(kw), "isosurface needs a function { … }");
    if (threshold != 0) function = "(" + function + ") - " + yaml_number(threshold);
    o.keys = ", expression: \"" + function + "\", contained_by: " + contained + ", max_gradient: " + yaml_number(max_gradient) +
             ", accuracy: " + yaml_number(accuracy);
    return o;
  }

  // function { … } as the text of strahl's expression language (docs/scene-format.md): POV-Ray's
  // x, y, z, numbers, operators and functions carry over; declared floats become their values.
  std::string function_text(const Token& kw) {
    expect_symbol("{", "after function");
    std::string s;
    for (int depth = 1;;) {
      const Token t = tokens_[pos_++];
      if (t.kind == TokenKind::End) throw Error(loc(kw), "function { is never closed");
      if (is_symbol(t, "{")) throw Error(loc(t), "'{' inside a function is not supported");
      if (is_symbol(t, "}") && --depth == 0) break;
      if (t.kind == TokenKind::Number) s += yaml_number(t.number);
      else if (t.kind == TokenKind::Symbol) s += t.text == "," ? ", " : " " + t.text + " ";
      else if (t.kind == TokenKind::Identifier) {
        if (t.text == "x" || t.text == "y" || t.text == "z" || is_function_name(t.text)) s += t.text;
        else if (t.text == "pi") s += yaml_number(kPi);
        else if (const auto it = symbols_.find(t.text); it != symbols_.end() && it->second.kind == Value::Kind::Number && it->second.num.dim == 1)
          s += "(" + yaml_number(it->second.num.f()) + ")";
        else throw Error(loc(t), "'" + t.text + "' in a function is not supported by strahl's POV-Ray importer");
      } else {
        throw Error(loc(t), describe(t) + " in a function is not supported");
      }
    }
    return s;
  }
  static bool is_function_name(const std::string& n) {
    static const std::set<std::string> kNames = {"sin", "cos", "tan", "asin", "acos", "atan", "exp", "log", "sqrt",
                                                 "abs", "floor", "atan2", "pow", "mod", "min", "max"};
    return kNames.count(n) > 0;
  }

  const PovOptions& options_;
  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
  std::vector<std::string> files_;
  std::map<std::string, Value> symbols_;
  std::map<std::string, Macro> macros_;
  std::vector<std::uint32_t> streams_;  // seed() and rand()
  std::map<std::string, std::string> unusable_;  // declared names holding what is not read: why
  std::vector<Control> controls_;
  std::set<std::string> warned_;
  long iterations_ = 0;
  int includes_ = 0;
  int in_vector_ = 0;
  int nesting_ = 0;
  Texture* noting_ = nullptr;  // the texture being read (note())
  double version_ = 0;  // #version (0: none)
  bool gamma_given_ = false;
  Parsed out_;
};

}  // namespace

Parsed parse_pov(const std::string& text, const std::string& name, const PovOptions& options) {
  return Reader(text, name, options).run();
}

}  // namespace strahl::pov
