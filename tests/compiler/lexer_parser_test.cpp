// Parsing: statement forms, one-line expressions, and error recovery (all errors reported).
#include <gtest/gtest.h>

#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/parser.hpp"
#include "test_support.hpp"

using namespace sandpaper;
using namespace sandpaper::compiler;

namespace {
MaterialSyntax parse_text(const std::string& text, Diagnostics& d) {
  auto f = std::make_shared<const SourceFile>("t.hmat", text);
  auto toks = lex(f, d);
  return parse(toks, f, d);
}
}  // namespace

TEST(Parser, MaterialBlockWithAllStatementKinds) {
  Diagnostics d;
  auto m = parse_text(R"(# comment line
material "a/b" {
  describes "intent"   # trailing comment
  like corduroy
  roughness 0.5
  grating period 3.2 mm hill 50% amplitude 1 N orientation 10 deg smoothing 0.1 mm
  heightmap "x.png" size 80 mm x 60 mm smoothing 0.2 mm amplitude 2 N repeat
  spring 200 N/m
  damper 2 N*s/m
  size 90 mm x 70 mm
  extrapolate
}
)", d);
  EXPECT_FALSE(d.has_errors()) << format_diagnostics(d);
  EXPECT_EQ(m.name, "a/b");
  ASSERT_EQ(m.statements.size(), 9u);
  const auto& g = std::get<GratingStmt>(m.statements[3].node);
  EXPECT_DOUBLE_EQ(g.period->si, 0.0032);
  EXPECT_DOUBLE_EQ(g.hill->si, 0.5);
  EXPECT_DOUBLE_EQ(g.smoothing->si, 0.0001);
  const auto& h = std::get<HeightmapStmt>(m.statements[4].node);
  EXPECT_EQ(h.path, "x.png");
  EXPECT_DOUBLE_EQ(h.height->si, 0.06);
  EXPECT_TRUE(h.repeat);
  EXPECT_EQ(m.statements[3].location.line, 6);
  EXPECT_EQ(m.statements[3].location.column, 3);
}

TEST(Parser, SemicolonsMakeAOneLineExpression) {
  Diagnostics d;
  auto m = parse_text("like corduroy; roughness 0.6 ;grating period 2 mm", d);
  EXPECT_FALSE(d.has_errors());
  ASSERT_EQ(m.statements.size(), 3u);
  EXPECT_EQ(std::get<LikeStmt>(m.statements[0].node).name, "corduroy");
}

TEST(Parser, BareNameMeansLike) {
  Diagnostics d;
  auto m = parse_text("  corduroy \n", d);
  EXPECT_FALSE(d.has_errors());
  ASSERT_EQ(m.statements.size(), 1u);
  EXPECT_EQ(std::get<LikeStmt>(m.statements[0].node).name, "corduroy");
}

TEST(Parser, BareNameAmongOtherStatementsIsUnknown) {
  Diagnostics d;
  parse_text("corduroy; roughness 0.5", d);
  ASSERT_EQ(d.all().size(), 1u);
  EXPECT_EQ(d.all()[0].code, "E0202");
}

TEST(Parser, AStatementNamedForAForceLawPointsToTheLaw) {
  for (const char* text : {"friction 0.5", "roughness 0.5; Friction static 0.6"}) {
    Diagnostics d;
    parse_text(text, d);
    ASSERT_EQ(d.all().size(), 1u) << text;
    EXPECT_EQ(d.all()[0].code, "E0202");
    EXPECT_NE(d.all()[0].suggestion.find("`physics Friction static 0.6 kinetic 0.4 press 1 N`"), std::string::npos)
        << d.all()[0].suggestion;
  }
  Diagnostics d;
  parse_text("nap-friction 0.5", d);
  ASSERT_EQ(d.all().size(), 1u);
  EXPECT_NE(d.all()[0].suggestion.find("`physics NapFriction` with static, kinetic, against_static, against_kinetic, press"),
            std::string::npos)
      << d.all()[0].suggestion;
}

TEST(Parser, ReportsEveryErrorNotJustTheFirst) {
  Diagnostics d;
  auto m = parse_text(R"(material "x" {
  roughnes 0.5
  grating period 2 mm hil 50%
  spring 200
  damper 2 N*s/m
  size 10 mm x
}
)", d);
  std::vector<std::string> got;
  for (const auto& x : d.all()) got.push_back(x.code);
  EXPECT_EQ(got, (std::vector<std::string>{"E0202", "E0209", "E0203", "E0215"}));
  // The good statement between the bad ones still parsed; bad ones were dropped.
  ASSERT_EQ(m.statements.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<DamperStmt>(m.statements[0].node));
  EXPECT_EQ(d.all()[0].suggestion, "did you mean `roughness`?");
  EXPECT_EQ(d.all()[1].suggestion, "did you mean `hill`?");
}

TEST(Parser, UnterminatedStringAndStrayCharacters) {
  Diagnostics d;
  parse_text("describes \"open\ngrating period 2 mm @", d);
  std::vector<std::string> got;
  for (const auto& x : d.all()) got.push_back(x.code);
  EXPECT_EQ(got[0], "E0101");
  EXPECT_NE(std::find(got.begin(), got.end(), "E0102"), got.end());
}

TEST(Parser, UnclosedBlockAndTrailingText) {
  Diagnostics d1;
  parse_text("material \"x\" {\n  spring 1 N/m\n", d1);
  ASSERT_EQ(d1.all().size(), 1u);
  EXPECT_EQ(d1.all()[0].code, "E0207");
  Diagnostics d2;
  parse_text("material \"x\" {\n}\nspring 1 N/m\n", d2);
  ASSERT_EQ(d2.all().size(), 1u);
  EXPECT_EQ(d2.all()[0].code, "E0208");
}

TEST(Parser, NumbersAndWordsSplitWhereExpected) {
  Diagnostics d;
  auto f = std::make_shared<const SourceFile>("t", "2.5mm 50% -3e-2 N*s/m 1e");
  auto t = lex(f, d);
  EXPECT_FALSE(d.has_errors());
  ASSERT_GE(t.size(), 8u);
  EXPECT_EQ(t[0].kind, TokenKind::Number);
  EXPECT_DOUBLE_EQ(t[0].number, 2.5);
  EXPECT_EQ(t[1].text, "mm");
  EXPECT_EQ(t[3].text, "%");
  EXPECT_DOUBLE_EQ(t[4].number, -0.03);
  EXPECT_EQ(t[5].text, "N*s/m");
  EXPECT_DOUBLE_EQ(t[6].number, 1);
  EXPECT_EQ(t[7].text, "e");
}
