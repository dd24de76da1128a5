// The material parser: the file, its block and statement list, and each statement dispatched
// (parser_impl.hpp says which file parses what).
#include "parser_impl.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "sandpaper/compiler/percepts.hpp"
#include "sandpaper/schema/diagnostic_codes.hpp"
#include "sandpaper/schema/force_laws.hpp"

namespace sandpaper::compiler {

using schema::Dimension;

std::string Quantity::text() const {
  std::ostringstream os;
  os << value;
  if (unit.empty()) return os.str();  // a plain number (e.g. the Attractor's swirl)
  return unit == "%" ? os.str() + "%" : os.str() + " " + unit;
}

const char* source_kind_word(SourceKind k) {
  switch (k) {
    case SourceKind::Measurement: return "measurement";
    case SourceKind::Standard: return "standard";
    case SourceKind::Publication: return "publication";
    case SourceKind::Derived: return "derived";
    case SourceKind::ByEar: return "by-ear";
  }
  return "?";
}

const char* source_kind_phrase(SourceKind k) {
  switch (k) {
    case SourceKind::Measurement: return "a measurement";
    case SourceKind::Standard: return "a standard";
    case SourceKind::Publication: return "a publication";
    case SourceKind::Derived: return "derived";
    case SourceKind::ByEar: return "designed by ear";
  }
  return "?";
}

bool is_metadata(const Statement& st) {
  return std::holds_alternative<FamilyStmt>(st.node) || std::holds_alternative<AliasStmt>(st.node) ||
         std::holds_alternative<LicenceStmt>(st.node) || std::holds_alternative<DeprecatedStmt>(st.node) ||
         std::holds_alternative<OverridesStmt>(st.node) || std::holds_alternative<AcceptStmt>(st.node);
}

bool carries_numbers(const Statement& st) {
  return !is_metadata(st) && !std::holds_alternative<DescribesStmt>(st.node) &&
         !std::holds_alternative<LikeStmt>(st.node) && !std::holds_alternative<ExtrapolateStmt>(st.node);
}

const std::vector<std::string>& statement_keywords() {
  static const std::vector<std::string> k = [] {
    std::vector<std::string> words{"describes", "like",   "roughness", "grating", "heightmap", "pattern",    "quantize",
                                   "spring",    "damper", "force",     "physics", "energy",    "size",       "extrapolate",
                                   "family",    "alias",  "licence",   "source",  "deprecated", "overrides",
                                   "accept"};
    for (const auto& w : percept_words()) words.emplace_back(w.word);
    return words;
  }();
  return k;
}

}  // namespace sandpaper::compiler

namespace sandpaper::compiler::parse_detail {

// file := End* (material_block | statement_list) End* Eof
MaterialSyntax Parser::file() {
  MaterialSyntax m;
  m.file = file_;
  skip_ends();
  if (peek().kind == TokenKind::Word && peek().text == "material") {
    material_block(m);
    skip_ends();
    if (peek().kind != TokenKind::Eof)
      diags_.error("E0208", peek().location, "text after the material block",
                   "a file holds one material; move this into the block or into a file of its own");
  } else {
    statement_list(m, /*in_block=*/false);
  }
  // A bare name as the whole expression means `like <name>` (`sandpaper run -e corduroy`).
  return m;
}

// material_block := 'material' STRING '{' End* (statement End+)* '}'
void Parser::material_block(MaterialSyntax& m) {
  next();  // 'material'
  if (peek().kind != TokenKind::String) {
    diags_.error("E0214", peek().location, std::string("expected the material's name as a string, found ") + describe(peek()),
                 "write material \"name\" { ... }");
  } else {
    m.name = peek().text;
    m.name_location = peek().location;
    next();
  }
  if (peek().kind != TokenKind::LBrace) {
    diags_.error("E0201", peek().location, std::string("expected '{' after the material name, found ") + describe(peek()),
                 "open the material's body with '{'");
    // Read the statements anyway so that their errors are reported too.
  } else {
    next();
  }
  statement_list(m, /*in_block=*/true);
  if (peek().kind == TokenKind::RBrace) {
    next();
  } else {
    diags_.error("E0207", m.name_location.file ? m.name_location : peek().location,
                 "the material block is not closed", "add '}' after its last statement");
  }
}

// statement_list := (statement? End)*   -- stops at '}' (in a block) or end of file
void Parser::statement_list(MaterialSyntax& m, bool in_block) {
  while (true) {
    skip_ends();
    const Token& t = peek();
    if (t.kind == TokenKind::Eof) return;
    if (t.kind == TokenKind::RBrace) {
      if (in_block) return;
      diags_.error("E0218", t.location, "unexpected '}' with no open material block", "remove it");
      next();
      continue;
    }
    try {
      if (t.kind == TokenKind::Word && t.text == "source") {
        source(m);
        expect_end("source");
        continue;
      }
      auto st = statement(m.statements.empty());
      expect_end(st.keyword);
      m.statements.push_back(std::move(st));
    } catch (const StatementError&) {
      recover(in_block);
    }
  }
}

// statement := describes | like | roughness | percept | grating | heightmap | pattern | quantize | spring | damper
//            | size | extrapolate
//            | NAME            (a lone name as the whole input: like NAME)
Statement Parser::statement(bool first) {
  const Token& kw = peek();
  if (first && (kw.kind == TokenKind::Number || kw.kind == TokenKind::Word) && adjacent_name_is_whole_input())
    return bare_joined_name();
  if (kw.kind != TokenKind::Word) {
    diags_.error("E0201", kw.location, std::string("expected a statement, found ") + describe(kw),
                 "statements start with a word such as grating, roughness or like");
    throw StatementError{};
  }
  Statement st;
  st.keyword = kw.text;
  st.location = kw.location;
  std::size_t start = pos_;
  next();
  const std::string& k = kw.text;
  if (k == "describes") st.node = describes();
  else if (k == "like") st.node = like();
  else if (k == "roughness") st.node = roughness();
  else if (const PerceptWord* w = find_percept_word(k)) st.node = percept(*w);
  else if (k == "grating") st.node = grating();
  else if (k == "heightmap") st.node = heightmap();
  else if (k == "spring") st.node = SpringStmt{quantity(Dimension::Stiffness, "the spring's stiffness")};
  else if (k == "damper") st.node = DamperStmt{quantity(Dimension::Damping, "the damper's damping")};
  else if (k == "size") st.node = size();
  else if (k == "extrapolate") st.node = ExtrapolateStmt{};
  else if (k == "force") st.node = law(schema::LawFamily::Force);
  else if (k == "physics") st.node = law(schema::LawFamily::Physics);
  else if (k == "energy") st.node = energy();
  else if (k == "pattern") st.node = pattern();
  else if (k == "quantize") st.node = quantize();
  else if (k == "family") st.node = family();
  else if (k == "alias") st.node = alias();
  else if (k == "licence" || k == "license") st.node = licence();
  else if (k == "deprecated") st.node = deprecated();
  // overrides := 'overrides'
  else if (k == "overrides") st.node = OverridesStmt{kw.location};
  else if (k == "accept") st.node = accept();
  else if (first && at_end_of_input()) {
    // The whole input is one name: a representative description.
    st.keyword = "like";
    st.node = LikeStmt{k, kw.location};
  } else {
    std::string guess = closest_match(k, statement_keywords());
    std::string help = guess.empty() ? "statements are: " + join(statement_keywords()) : "did you mean `" + guess + "`?";
    if (const schema::LawDef* law = law_named_by(k)) help = law_statement_help(*law);
    diags_.error("E0202", kw.location, "unknown statement '" + k + "'", help);
    throw StatementError{};
  }
  st.text = span_text(start, pos_);
  return st;
}

// Whether token i ends where token i + 1 starts, on the same line.
bool Parser::touches_next(std::size_t i) const {
  if (i + 1 >= toks_.size()) return false;
  const Token& a = toks_[i];
  const Token& b = toks_[i + 1];
  if (b.kind != TokenKind::Word && b.kind != TokenKind::Number) return false;
  return a.location.line == b.location.line && a.location.column + a.location.length == b.location.column;
}

std::string Parser::joined_name() {
  std::string name = peek().text;
  while (touches_next(pos_)) {
    next();
    name += peek().text;
  }
  next();
  return name;
}

// A name starting with a digit (2StripesWeak) as the whole input: like NAME.
bool Parser::adjacent_name_is_whole_input() const {
  std::size_t i = pos_;
  if (!touches_next(i)) return false;
  while (touches_next(i)) ++i;
  while (i + 1 < toks_.size() && toks_[i + 1].kind == TokenKind::End) ++i;
  return i + 1 >= toks_.size() || toks_[i + 1].kind == TokenKind::Eof;
}

Statement Parser::bare_joined_name() {
  Statement st;
  st.keyword = "like";
  st.location = peek().location;
  SourceLocation at = peek().location;
  std::string name = joined_name();
  at.length = static_cast<int>(name.size());
  st.node = LikeStmt{name, at};
  st.text = name;
  return st;
}

void Parser::expect_end(const std::string& keyword) {
  const Token& t = peek();
  if (t.kind == TokenKind::End || t.kind == TokenKind::Eof || t.kind == TokenKind::RBrace) return;
  diags_.error("E0210", t.location, std::string("unexpected ") + describe(t) + " after the " + keyword + " statement",
               "put one statement on each line, or separate statements with ';'");
  throw StatementError{};
}

// Skip to the end of the statement; leave a '}' for the block to see.
void Parser::recover(bool in_block) {
  while (peek().kind != TokenKind::End && peek().kind != TokenKind::Eof && !(in_block && peek().kind == TokenKind::RBrace))
    next();
}

bool Parser::at_end_of_input() const {
  std::size_t i = pos_;
  while (i < toks_.size() && toks_[i].kind == TokenKind::End) ++i;
  return i >= toks_.size() || toks_[i].kind == TokenKind::Eof;
}

std::string Parser::span_text(std::size_t b, std::size_t e) const {
  std::string out;
  for (std::size_t i = b; i < e; ++i) {
    if (!out.empty() && toks_[i].text != "%") out += ' ';
    out += toks_[i].kind == TokenKind::String ? "\"" + toks_[i].text + "\"" : toks_[i].text;
  }
  return out;
}

}  // namespace sandpaper::compiler::parse_detail

namespace sandpaper::compiler {

MaterialSyntax parse(const std::vector<Token>& tokens, const std::shared_ptr<const SourceFile>& file,
                     Diagnostics& diags) {
  if (tokens.empty()) throw InternalError("parse: token stream without Eof");
  return parse_detail::Parser(tokens, file, diags).file();
}

}  // namespace sandpaper::compiler
