// The statements that describe a library entry rather than what it feels like.
#include "parser_impl.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "sandpaper/compiler/percepts.hpp"
#include "sandpaper/schema/diagnostic_codes.hpp"
#include "sandpaper/schema/force_laws.hpp"

namespace sandpaper::compiler::parse_detail {

// source := 'source' KIND STRING      -- sources the statement before it
// KIND := 'measurement' | 'standard' | 'publication' | 'derived' | 'by-ear'
void Parser::source(MaterialSyntax& m) {
  const Token& kw = next();
  static const std::vector<std::pair<std::string, SourceKind>> kinds{
      {"measurement", SourceKind::Measurement}, {"standard", SourceKind::Standard},
      {"publication", SourceKind::Publication}, {"derived", SourceKind::Derived},
      {"by-ear", SourceKind::ByEar}};
  std::vector<std::string> words;
  for (const auto& [w, k] : kinds) words.push_back(w);
  const Token& k = peek();
  std::optional<SourceKind> kind;
  for (const auto& [w, sk] : kinds)
    if (k.kind == TokenKind::Word && k.text == w) kind = sk;
  if (!kind) {
    std::string guess = k.kind == TokenKind::Word ? closest_match(k.text, words) : "";
    diags_.error("E0213", k.location, std::string("expected the kind of source, found ") + describe(k),
                 guess.empty() ? "write source KIND \"text\", KIND one of " + join(words) +
                                     " (by-ear: chosen by judgement, said plainly)"
                               : "did you mean `" + guess + "`?");
    throw StatementError{};
  }
  next();
  if (peek().kind != TokenKind::String) {
    diags_.error("E0214", peek().location, std::string("expected the source as a quoted text, found ") + describe(peek()),
                 "write source " + k.text + " \"Minsky 1995, Table 8\" (who measured it, which standard or paper, "
                 "the arithmetic, or why it was chosen)");
    throw StatementError{};
  }
  SourceNote note{*kind, next().text, kw.location};
  if (m.statements.empty()) {
    diags_.error("E0212", kw.location, "`source` with no statement before it to source",
                 "write the source on the line after the statement whose numbers it explains");
    throw StatementError{};
  }
  m.statements.back().sources.push_back(std::move(note));
}

// family := 'family' WORD
FamilyStmt Parser::family() {
  if (peek().kind != TokenKind::Word) {
    diags_.error("E0217", peek().location, std::string("expected a family name, found ") + describe(peek()),
                 "write family textiles (the families are listed in library/library.toml)");
    throw StatementError{};
  }
  const Token& t = next();
  return FamilyStmt{t.text, t.location};
}

// alias := 'alias' NAME
AliasStmt Parser::alias() {
  auto [name, at] = entry_name("another name for the entry", "write alias wide-wale-corduroy (words and numbers written together, no spaces)");
  return AliasStmt{name, at};
}

// An entry's NAME (the `like` rule: words and numbers written together), with its location.
std::pair<std::string, SourceLocation> Parser::entry_name(const std::string& what, const std::string& help) {
  const Token& t = peek();
  if (t.kind != TokenKind::Word && t.kind != TokenKind::Number) {
    diags_.error("E0217", t.location, "expected " + what + ", found " + describe(t), help);
    throw StatementError{};
  }
  SourceLocation at = t.location;
  std::string name = joined_name();
  at.length = static_cast<int>(name.size());
  return {name, at};
}

// licence := ('licence' | 'license') STRING     -- an SPDX identifier such as "CC0-1.0"
LicenceStmt Parser::licence() {
  if (peek().kind != TokenKind::String) {
    diags_.error("E0214", peek().location, std::string("expected the licence as a quoted SPDX identifier, found ") + describe(peek()),
                 "write licence \"CC0-1.0\" (or \"CC-BY-4.0\", ...)");
    throw StatementError{};
  }
  const Token& t = next();
  return LicenceStmt{t.text, t.location};
}

// accept := 'accept' CODE STRING     -- CODE a registered warning code (W0350), STRING the reason
AcceptStmt Parser::accept() {
  const std::string help = "write accept W0350 \"why this entry means what the warning says\": a warning's code, then the reason a reviewer reads";
  if (peek().kind != TokenKind::Word) {
    diags_.error("E0220", peek().location, std::string("expected the code of the warning to accept, found ") + describe(peek()), help);
    throw StatementError{};
  }
  const Token& code = next();
  const auto* known = schema::find_diagnostic_code(code.text);
  if (!known || known->severity != schema::DiagnosticSeverity::Warning) {
    std::vector<std::string> warnings;
    for (const auto& d : schema::diagnostic_codes())
      if (d.severity == schema::DiagnosticSeverity::Warning) warnings.emplace_back(d.code);
    const auto guess = closest_match(code.text, warnings);
    diags_.error("E0220", code.location,
                 known ? "`accept` takes a warning's code; " + code.text + " is an error, which no entry can accept"
                       : "no warning has the code '" + code.text + "'",
                 known ? "fix what " + code.text + " says" : guess.empty() ? "the codes are listed in schema/LANGUAGE.md, \"Diagnostics\"" : "did you mean " + guess + "?");
    throw StatementError{};
  }
  if (peek().kind != TokenKind::String || peek().text.find_first_not_of(" \t") == std::string::npos) {
    diags_.error("E0220", peek().location, "`accept " + code.text + "` needs the reason, quoted, found " + describe(peek()), help);
    throw StatementError{};
  }
  const Token& reason = next();
  return AcceptStmt{code.text, reason.text, code.location};
}

// deprecated := 'deprecated' 'replaced-by' NAME
DeprecatedStmt Parser::deprecated() {
  if (!(peek().kind == TokenKind::Word && peek().text == "replaced-by")) {
    diags_.error("E0216", peek().location, std::string("expected `replaced-by`, found ") + describe(peek()),
                 "write deprecated replaced-by NAME, naming the entry to use instead");
    throw StatementError{};
  }
  next();
  auto [name, at] = entry_name("the replacement entry's name", "write deprecated replaced-by NAME");
  return DeprecatedStmt{name, at};
}

// describes := 'describes' STRING
DescribesStmt Parser::describes() {
  if (peek().kind != TokenKind::String) {
    diags_.error("E0214", peek().location, std::string("expected a quoted description, found ") + describe(peek()),
                 "write describes \"what this material is meant to feel like\"");
    throw StatementError{};
  }
  return DescribesStmt{next().text};
}

// like := 'like' NAME
// NAME := (WORD | NUMBER)+ written together: thesis stimulus names such as 2StripesWeak and
// barsB2W2_.25 lex as numbers and words with no space between them.
LikeStmt Parser::like() {
  const Token& t = peek();
  if (t.kind == TokenKind::Word || (t.kind == TokenKind::Number && touches_next(pos_))) {
    SourceLocation at = t.location;
    std::string name = joined_name();
    at.length = static_cast<int>(name.size());
    return LikeStmt{name, at};
  }
  diags_.error("E0217", peek().location, std::string("expected a library entry's name, found ") + describe(peek()),
               "write like corduroy (see `sandpaper library` for the names)");
  throw StatementError{};
}

}  // namespace sandpaper::compiler::parse_detail
