#pragma once
// The material parser (tokens -> syntax), one part a file: parser.cpp reads the file, the material
// block and the statement list and dispatches each statement; parse_metadata.cpp the statements that
// describe an entry (source, family, alias, licence, accept, deprecated, describes, like);
// parse_physical.cpp those that set what is felt (roughness and the perceptual words, grating,
// heightmap, force laws, energy, pattern, quantize, size, quantities). Each function has the grammar
// rule it parses above it. Internal to the compiler library.
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/compiler/percepts.hpp"
#include "sandpaper/schema/force_laws.hpp"
#include "token_cursor.hpp"

namespace sandpaper::compiler::parse_detail {

using schema::Dimension;

// The range of a quantity in SI units (see quantity()).
constexpr double kLeastQuantitySI = 1e-12;
constexpr double kGreatestQuantitySI = 1e12;

class Parser : TokenCursor {
 public:
  Parser(const std::vector<Token>& tokens, std::shared_ptr<const SourceFile> file, Diagnostics& diags)
      : TokenCursor(tokens), file_(std::move(file)), diags_(diags) {}

  MaterialSyntax file();

 private:
  void material_block(MaterialSyntax& m);

  void statement_list(MaterialSyntax& m, bool in_block);

  Statement statement(bool first);

  void source(MaterialSyntax& m);

  FamilyStmt family();

  AliasStmt alias();

  std::pair<std::string, SourceLocation> entry_name(const std::string& what, const std::string& help);

  LicenceStmt licence();

  AcceptStmt accept();

  DeprecatedStmt deprecated();

  DescribesStmt describes();

  LikeStmt like();

  bool touches_next(std::size_t i) const;

  std::string joined_name();

  bool adjacent_name_is_whole_input() const;

  Statement bare_joined_name();

  RoughnessStmt roughness();

  PerceptStmt percept(const PerceptWord& w);

  GratingStmt grating();

  HeightmapStmt heightmap();

  LawStmt law(schema::LawFamily family);

  EnergyStmt energy();

  static const schema::LawDef* law_named_by(const std::string& word);

  static std::string law_statement_help(const schema::LawDef& law);

  static std::string join(const std::vector<std::string>& xs);

  PatternStmt pattern();

  QuantizeStmt quantize();

  PlainNumber plain_number(const char* what, const char* example_text);

  void set_once(std::optional<PlainNumber>& slot, const Token& opt, const char* what, const char* example_text);

  SizeStmt size();

  Quantity quantity(Dimension dim, const char* what);

  void set_once(std::optional<Quantity>& slot, const Token& opt, Dimension dim, const char* what);

  [[noreturn]] void unknown_option(const char* stmt, const Token& o, const std::vector<std::string>& opts);

  void expect_end(const std::string& keyword);

  void recover(bool in_block);

  bool at_end_of_input() const;

  static std::string example(Dimension d);

  std::string span_text(std::size_t b, std::size_t e) const;

  std::shared_ptr<const SourceFile> file_;
  Diagnostics& diags_;
};

}  // namespace sandpaper::compiler::parse_detail
