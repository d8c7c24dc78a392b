// The POV-Ray importer's directives (pov_parser.h), carried out where they stand: #declare/#local,
// #undef, #version, #include, #if/#elseif/#else, #ifdef/#ifndef, #switch/#case/#range/#break,
// #while, #for, #macro and its calls, #debug/#warning/#error, #default.

#include "strahl/scene/pov/pov_parser.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

namespace strahl::pov {

namespace fs = std::filesystem;

void Parser::directive() {
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
      jump(c.loop, loc(d));
      unwind_to(controls_.size() - 1);
    } else if (c.name == "while") {
      jump(c.loop, loc(d));
      controls_.pop_back();
    } else if (c.name == "for") {
      const double v = symbol_number(c.var, loc(d)) + c.step;
      symbols_[c.var] = Value{Value::Kind::Number, number(v), {}, {}, {}};
      if (c.step > 0 ? v <= c.end : v >= c.end) {
        jump(c.loop, loc(d));
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

// Reading goes on at `to`: a loop's start, a macro's body or where it returns, a declaration read
// again, an included file. What was read since the last jump counts towards the bound on tokens
// read (a loop may skip far on each turn: its turns alone do not bound the work).
void Parser::jump(std::size_t to, const FileLoc& where) {
  if (pos_ > segment_) tokens_read_ += pos_ - segment_;
  if (tokens_read_ > options_.max_tokens_read)
    throw Error(where, "the scene's loops and macros read more than " + std::to_string(options_.max_tokens_read) +
                           " tokens (an endless #while?)");
  pos_ = to;
  segment_ = to;
}

void Parser::count_iteration(const FileLoc& loc) {
  if (++iterations_ > options_.max_loop_iterations)
    throw Error(loc, "more than " + std::to_string(options_.max_loop_iterations) + " loop iterations (an endless #while?)");
}

bool Parser::condition(const Token& d) {
  const Num c = expression();
  if (c.dim != 1) throw Error(loc(d), "#" + d.text + " needs a float condition, not a vector");
  return c.f() != 0;
}

// Skips a branch not taken: to the matching #else (then reads on), a true #elseif, or #end.
void Parser::skip_to_else(const Token& d) {
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

void Parser::skip_to_end(const Token& d) {
  while (skip_to_directive(d, Stop::End).text != "end") {
  }
}

// #switch (value): on at the first #case (v) with v = value, #range (lo, hi) holding it, or
// #else; then through the clauses after it (POV-Ray's fall-through) to #break or #end.
void Parser::switch_directive(const Token& d) {
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

bool Parser::case_holds(const Token& t, double value) {
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

// Moves past the next #end (or the directives `stop` names) at this level.
Token Parser::skip_to_directive(const Token& d, Stop stop) {
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
void Parser::declare(const Token& name) {
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
    jump(start, loc(name));
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

// Closes the frames opened since `depth` (a declaration given up): macros give back what they hid.
void Parser::unwind_to(std::size_t depth) {
  while (controls_.size() > depth) {
    Control& c = controls_.back();
    for (auto it = c.hidden.rbegin(); it != c.hidden.rend(); ++it) {
      if (it->second) symbols_[it->first] = std::move(*it->second);
      else symbols_.erase(it->first);
    }
    controls_.pop_back();
  }
}

// A macro's parameter or #local name: what it was is given back when the macro returns.
void Parser::hide_in_macro(const std::string& name) {
  for (auto c = controls_.rbegin(); c != controls_.rend(); ++c) {
    if (c->name != "macro") continue;
    for (const auto& h : c->hidden)
      if (h.first == name) return;
    const auto it = symbols_.find(name);
    c->hidden.emplace_back(name, it == symbols_.end() ? std::nullopt : std::optional<Value>(it->second));
    return;
  }
}

// NAME(arguments): the arguments are evaluated, the parameters declared (hiding what they
// named) and reading goes on in the body until its #end, which returns here.
void Parser::call_macro(const Token& name) {
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
  jump(m.body, loc(name));
}

// After a value read from a macro's body: its #end (and any directives before it) must follow.
void Parser::finish_macro(std::size_t depth, const Token& name) {
  while (controls_.size() > depth) {
    if (raw().kind != TokenKind::Directive)
      throw Error(loc(raw()), "the macro " + name.text + " gives more than one value here (expected its #end)");
    directive();
  }
}

void Parser::include(const Token& file, std::size_t at) {
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
  jump(at, loc(file));
  for (Control& c : controls_)
    if (c.loop > at) c.loop = std::size_t(std::ptrdiff_t(c.loop) + delta);
  for (auto& [name, m] : macros_)
    if (m.body > at) m.body = std::size_t(std::ptrdiff_t(m.body) + delta);
}

}  // namespace strahl::pov
