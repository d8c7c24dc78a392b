// The POV-Ray importer's parser (pov_parser.h): its entry, and reading tokens — the next one after
// any directives before it, expected symbols, what was left out (warnings, a texture's notes), and
// skipping what is read past.

#include "strahl/scene/pov/pov_parser.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace strahl::pov {

namespace fs = std::filesystem;

Parser::Parser(const std::string& text, const std::string& name, const PovOptions& options) : options_(options) {
  tokens_ = text_tokens(text, name);
  for (const auto& [declared, value] : options.declares) symbols_[declared] = Value{Value::Kind::Number, number(value), {}, {}, {}};
}

Parsed Parser::run() {
  while (peek().kind != TokenKind::End) statement();
  if (!controls_.empty()) throw Error(controls_.back().loc, "this #" + controls_.back().name + " has no #end");
  if (!gamma_given_ && !(version_ >= 3.7))
    out_.warnings.push_back(files_.front() +
                            ": no #version 3.7 and no assumed_gamma: POV-Ray draws this scene with its legacy "
                            "gamma, writing the linear values to 8-bit images (strahl's --linear does the same)");
  return std::move(out_);
}

std::vector<Token> Parser::read_tokens(const fs::path& path, const FileLoc& from) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw Error(from.file.empty() ? FileLoc{path.string()} : from, "cannot open '" + path.string() + "' (no such file)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(from.file.empty() ? FileLoc{path.string()} : from, "cannot open '" + path.string() + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return text_tokens(text.str(), path.string());
}

std::vector<Token> Parser::text_tokens(const std::string& text, const std::string& name) {
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos)
    throw Error(FileLoc{name, 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(nul), '\n'))},
                "not a text file (a NUL byte; POV-Ray scenes are text)");
  files_.push_back(name);
  return tokenize(text, name, std::uint32_t(files_.size() - 1));
}

// The next token after carrying out any directives before it.
// (A copy: a directive carried out later, an #include, may move the tokens.)
Token Parser::peek() {
  while (tokens_[pos_].kind == TokenKind::Directive) directive();
  const Token& t = tokens_[pos_];
  if (t.kind == TokenKind::Identifier && !unusable_.empty())
    if (const auto it = unusable_.find(t.text); it != unusable_.end())
      throw Unusable(loc(t), "'" + t.text + "' cannot be used: its declaration holds what strahl's POV-Ray importer does "
                                            "not read (" + it->second + ")");
  return t;
}

// A name right after a directive (#declare NAME, #ifdef (NAME) …): read as it stands.
Token Parser::name_after_directive(const char* what) {
  const Token t = tokens_[pos_];
  if (t.kind != TokenKind::Identifier) throw Error(loc(t), std::string("expected a name ") + what + ", found " + describe(t));
  ++pos_;
  return t;
}

Token Parser::next() {
  Token t = peek();
  if (t.kind != TokenKind::End) ++pos_;
  return t;
}

bool Parser::accept_symbol(const char* s) {
  if (!is_symbol(peek(), s)) return false;
  ++pos_;
  return true;
}

bool Parser::accept_raw_symbol(const char* s) {  // without carrying out directives (an expression's end)
  if (!is_symbol(raw(), s)) return false;
  ++pos_;
  return true;
}

void Parser::expect_symbol(const char* s, const char* where) {
  const Token t = next();
  if (!is_symbol(t, s)) throw Error(loc(t), std::string("expected '") + s + "' " + where + ", found " + describe(t));
}

std::string Parser::describe(const Token& t) {
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

void Parser::unsupported(const Token& t, const std::string& where) {
  if (t.kind == TokenKind::End) throw Error(loc(t), "the file ends inside " + where + " (a '}' is missing)");
  throw Error(loc(t), "'" + t.text + "'" + (where.empty() ? "" : " in " + where) +
                         " is not supported by strahl's POV-Ray importer (docs/pov-import.md)");
}

// A texture's note (Texture::notes) while one is being read, else a warning.
void Parser::note(const FileLoc& where, const std::string& message) {
  if (!noting_) return warn(where, message);
  const std::string n = where.str() + ": " + message;
  if (std::find(noting_->notes.begin(), noting_->notes.end(), n) == noting_->notes.end()) noting_->notes.push_back(n);
}

void Parser::warn(const FileLoc& loc, const std::string& message) {
  const std::string w = loc.str() + ": " + message;
  if (warned_.insert(message).second) out_.warnings.push_back(w);
}

// Past the ';' that ends a declaration, if one does (before the next directive).
bool Parser::skip_to_semicolon() {
  for (int level = 0;;) {
    const Token& t = tokens_[pos_];
    if (t.kind == TokenKind::End || t.kind == TokenKind::Directive) return false;
    ++pos_;
    if (is_symbol(t, "(") || is_symbol(t, "{") || is_symbol(t, "<")) ++level;
    if (is_symbol(t, ")") || is_symbol(t, "}") || is_symbol(t, ">")) --level;
    if (level <= 0 && is_symbol(t, ";")) return true;
  }
}

// A layered texture's further layers (texture { … } texture { … }): read past. Returns whether
// there were any.
bool Parser::skip_layers() {
  bool any = false;
  while (is_word(tokens_[pos_], "texture") && pos_ + 1 < tokens_.size() && is_symbol(tokens_[pos_ + 1], "{")) {
    ++pos_;
    skip_balanced("{", "}");
    any = true;
  }
  return any;
}

// From an opening bracket to its partner, reading nothing.
void Parser::skip_balanced(const char* open, const char* close) {
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

void Parser::skip_block() {
  expect_symbol("{", "");
  for (int depth = 1; depth > 0;) {
    const Token t = next();
    if (t.kind == TokenKind::End) throw Error(loc(t), "a block is never closed (no })");
    if (is_symbol(t, "{")) ++depth;
    if (is_symbol(t, "}")) --depth;
  }
}

Parsed parse_pov(const std::string& text, const std::string& name, const PovOptions& options) {
  return Parser(text, name, options).run();
}

}  // namespace strahl::pov
