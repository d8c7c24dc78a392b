#include "strahl/scene/pov/pov_lexer.h"

#include <cctype>
#include <cerrno>
#include <cstdlib>

namespace strahl::pov {

namespace {

bool ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

class Lexer {
 public:
  Lexer(const std::string& text, const std::string& file, std::uint32_t index) : s_(text), file_(file), index_(index) {}

  std::vector<Token> run() {
    std::vector<Token> out;
    for (;;) {
      skip_space_and_comments();
      Token t;
      t.file = index_;
      t.line = line_;
      t.column = column_;
      const FileLoc loc = here();
      if (i_ >= s_.size()) {
        out.push_back(std::move(t));
        return out;
      }
      const char c = s_[i_];
      if (digit(c) || (c == '.' && i_ + 1 < s_.size() && digit(s_[i_ + 1]))) {
        t.kind = TokenKind::Number;
        t.number = number(loc);
      } else if (ident_start(c)) {
        t.kind = TokenKind::Identifier;
        t.text = identifier();
      } else if (c == '#') {
        advance();
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t')) advance();  // "# declare" is allowed
        if (i_ >= s_.size() || !ident_start(s_[i_])) throw Error(loc, "expected a directive name after '#'");
        t.kind = TokenKind::Directive;
        t.text = identifier();
      } else if (c == '"') {
        t.kind = TokenKind::String;
        t.text = string(loc);
      } else {
        t.kind = TokenKind::Symbol;
        t.text = symbol(loc);
      }
      out.push_back(std::move(t));
    }
  }

 private:
  FileLoc here() const { return FileLoc{file_, line_, column_}; }

  void advance() {
    if (s_[i_] == '\n') {
      ++line_;
      column_ = 1;
    } else if ((static_cast<unsigned char>(s_[i_]) & 0xC0) != 0x80) {
      ++column_;  // (UTF-8 continuation bytes do not start a column)
    }
    ++i_;
  }

  void skip_space_and_comments() {
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v') {
        advance();
      } else if (c == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '/') {
        while (i_ < s_.size() && s_[i_] != '\n') advance();
      } else if (c == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '*') {
        const FileLoc start = here();
        int depth = 0;
        do {
          if (i_ + 1 < s_.size() && s_[i_] == '/' && s_[i_ + 1] == '*') {
            ++depth;
            advance();
          } else if (i_ + 1 < s_.size() && s_[i_] == '*' && s_[i_ + 1] == '/') {
            --depth;
            advance();
          }
          advance();
        } while (depth > 0 && i_ < s_.size());
        if (depth > 0) throw Error(start, "this comment is never closed (no */)");
      } else {
        return;
      }
    }
  }

  std::string identifier() {
    const std::size_t start = i_;
    while (i_ < s_.size() && ident_char(s_[i_])) advance();
    return s_.substr(start, i_ - start);
  }

  double number(const FileLoc& loc) {
    const std::size_t start = i_;
    while (i_ < s_.size() && digit(s_[i_])) advance();
    if (i_ < s_.size() && s_[i_] == '.') {
      advance();
      while (i_ < s_.size() && digit(s_[i_])) advance();
    }
    if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
      std::size_t j = i_ + 1;
      if (j < s_.size() && (s_[j] == '+' || s_[j] == '-')) ++j;
      if (j < s_.size() && digit(s_[j])) {
        while (i_ < j) advance();
        while (i_ < s_.size() && digit(s_[i_])) advance();
      }
    }
    const std::string text = s_.substr(start, i_ - start);
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (errno == ERANGE || end != text.c_str() + text.size())
      throw Error(loc, "number '" + text + "' is out of range");
    return v;
  }

  std::string string(const FileLoc& loc) {
    advance();  // the opening quote
    std::string out;
    for (;;) {
      if (i_ >= s_.size()) throw Error(loc, "this string is never closed (no \" before the end of the file)");
      const char c = s_[i_];
      advance();
      if (c == '"') return out;
      if (c == '\\' && i_ < s_.size()) {
        const char e = s_[i_];
        advance();
        out += e == 'n' ? '\n' : e == 't' ? '\t' : e;
      } else {
        out += c;
      }
    }
  }

  std::string symbol(const FileLoc& loc) {
    const char c = s_[i_];
    static const std::string singles = "{}<>,()[]+-*/=;.?:!&|";
    if (singles.find(c) == std::string::npos) {
      const unsigned char u = static_cast<unsigned char>(c);
      throw Error(loc, u >= 0x20 && u < 0x7F ? std::string("unexpected character '") + c + "'"
                                              : "unexpected byte " + std::to_string(u) + " (POV-Ray scene files are text)");
    }
    advance();
    if (i_ < s_.size() && s_[i_] == '=' && (c == '<' || c == '>' || c == '!')) {
      advance();
      return std::string(1, c) + "=";
    }
    return std::string(1, c);
  }

  const std::string& s_;
  const std::string& file_;
  std::uint32_t index_;
  std::size_t i_ = 0;
  int line_ = 1, column_ = 1;
};

}  // namespace

std::vector<Token> tokenize(const std::string& text, const std::string& file, std::uint32_t index) {
  return Lexer(text, file, index).run();
}

}  // namespace strahl::pov
