#pragma once
// Phase 1: text -> tokens. Statements end at a newline or `;`; `#` starts a comment to the end of
// the line. Lexical errors are reported and skipped so that parsing can go on (schema/LANGUAGE.md).
#include <memory>
#include <string>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"

namespace sandpaper::compiler {

enum class TokenKind {
  Word,       // a keyword, a name or a unit: [A-Za-z_%][A-Za-z0-9_\-/*]*  ("grating", "N*s/m", "%")
  Number,     // [+-]?digits[.digits][e[+-]digits]
  String,     // "..." with \" and \\ escapes; `text` holds the unescaped contents
  LBrace,
  RBrace,
  Comma,      // only with LexOptions::commas (workspace files: `at -60 mm, 0 mm`)
  End,        // end of a statement: newline or ';'
  Eof,
};

struct Token {
  TokenKind kind;
  std::string text;    // the word, the number as written, or the string's contents
  double number = 0;   // for Number
  SourceLocation location;
};

struct LexOptions {
  // ',' is a token (workspace files) rather than an unexpected character (material files).
  bool commas = false;
};

std::vector<Token> lex(const std::shared_ptr<const SourceFile>& file, Diagnostics& diags, LexOptions options = {});

const char* token_kind_name(TokenKind k);

}  // namespace sandpaper::compiler
