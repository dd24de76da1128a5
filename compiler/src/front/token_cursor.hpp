#pragma once
// Reading tokens one at a time, for the material parser and the workspace parser: the token at
// hand, stepping past it (never past Eof), skipping line ends, a token as a message names it, and
// the abandoning of a statement whose error is already recorded. Internal to the compiler library.
#include <cstddef>
#include <string>
#include <vector>

#include "sandpaper/compiler/lexer.hpp"

namespace sandpaper::compiler {

// Thrown inside a statement to abandon it; the diagnostic has already been recorded.
struct StatementError {};

class TokenCursor {
 protected:
  // `tokens` ends with Eof (the parsers' entry points check it).
  explicit TokenCursor(const std::vector<Token>& tokens) : toks_(tokens) {}

  const Token& peek() const { return toks_[pos_]; }
  const Token& next() {
    const Token& t = toks_[pos_];
    if (pos_ + 1 < toks_.size()) ++pos_;  // never step past Eof
    return t;
  }
  void skip_ends() {
    while (peek().kind == TokenKind::End) next();
  }
  // "'corduroy'", "the number 2.5", "the string \"x\"", or the token kind's name.
  static std::string describe(const Token& t) {
    switch (t.kind) {
      case TokenKind::Word: return "'" + t.text + "'";
      case TokenKind::Number: return "the number " + t.text;
      case TokenKind::String: return "the string \"" + t.text + "\"";
      default: return token_kind_name(t.kind);
    }
  }

  const std::vector<Token>& toks_;
  std::size_t pos_ = 0;
};

}  // namespace sandpaper::compiler
