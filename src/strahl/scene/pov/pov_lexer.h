#pragma once
// The tokens of POV-Ray's scene description language (SDL), for the importer (pov_scene.h):
// numbers, strings, identifiers and keywords, directives (`#declare` as one token) and symbols.
// Comments (`// …`, `/* … */`, which nest in POV-Ray) are skipped.

#include <cstdint>
#include <string>
#include <vector>

#include "strahl/util/error.h"

namespace strahl::pov {

enum class TokenKind { Number, String, Identifier, Directive, Symbol, End };

struct Token {
  TokenKind kind = TokenKind::End;
  std::uint32_t file = 0;  // the reader's index of the file it is in
  int line = 0, column = 0;
  double number = 0;  // TokenKind::Number
  std::string text;   // identifier, directive name (without '#'), string contents or symbol
};

// The tokens of `text`, ending with one TokenKind::End; `file` names it in errors, `index` is
// what the tokens' `file` holds. Throws strahl::Error at an unexpected character, an
// unterminated string or comment, a number out of range.
std::vector<Token> tokenize(const std::string& text, const std::string& file, std::uint32_t index);

}  // namespace strahl::pov
