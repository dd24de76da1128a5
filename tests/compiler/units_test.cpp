// Unit factors against independent definitions, and the rule that quantities carry units.
#include <cmath>

#include <gtest/gtest.h>

#include "sandpaper/schema/units.hpp"
#include "test_support.hpp"

using namespace sandpaper;
using schema::Dimension;

TEST(Units, FactorsMatchTheirDefinitions) {
  struct Case { const char* name; Dimension dim; double si; };
  // 1 in = 25.4 mm exactly; 1 oz = 28.349523125 g; g_n = 9.80665 m/s^2.
  const Case cases[] = {
      {"m", Dimension::Length, 1},          {"cm", Dimension::Length, 0.01},
      {"mm", Dimension::Length, 0.001},     {"um", Dimension::Length, 1e-6},
      {"in", Dimension::Length, 0.0254},    {"N", Dimension::Force, 1},
      {"mN", Dimension::Force, 0.001},      {"gf", Dimension::Force, 0.00980665},
      {"ozf", Dimension::Force, 0.27801385095378125},
      {"N/m", Dimension::Stiffness, 1},     {"N/mm", Dimension::Stiffness, 1000},
      {"N*s/m", Dimension::Damping, 1},     {"deg", Dimension::Angle, 0.017453292519943295},
      {"%", Dimension::Fraction, 0.01},
      // The thesis joystick: 0.490909 gf per joystick unit, 4 per program unit (Table 6).
      {"ju", Dimension::Force, 0.490909 * 0.00980665}, {"pu", Dimension::Force, 4 * 0.490909 * 0.00980665},
      {"kg", Dimension::Mass, 1},           {"g", Dimension::Mass, 0.001},
      {"s", Dimension::Time, 1},            {"ms", Dimension::Time, 0.001},
      {"J", Dimension::Energy, 1},          {"mJ", Dimension::Energy, 0.001},
      {"W", Dimension::Power, 1},           {"mW", Dimension::Power, 0.001},
      {"m/s", Dimension::Speed, 1},         {"mm/s", Dimension::Speed, 0.001},
  };
  for (const auto& c : cases) {
    auto u = schema::find_unit(c.name);
    ASSERT_TRUE(u) << c.name;
    EXPECT_EQ(u->dimension, c.dim) << c.name;
    EXPECT_NEAR(u->to_si, c.si, 1e-15 * std::abs(c.si) + 1e-18) << c.name;
  }
  EXPECT_EQ(schema::all_units().size(), std::size(cases));
  EXPECT_FALSE(schema::find_unit("MN"));  // case matters: mega-newtons are not milli-newtons
}

TEST(Units, QuantitiesAreConvertedToSI) {
  auto r = test::shipped_compiler().compile_text("grating period 0.1 in hill 25% amplitude 100 gf orientation 90 deg");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_DOUBLE_EQ(test::provenance(*r.program, "texture.period").value_si, 0.00254);
  EXPECT_DOUBLE_EQ(test::provenance(*r.program, "texture.hill").value_si, 0.25);
  EXPECT_DOUBLE_EQ(test::provenance(*r.program, "texture.max_lateral_force").value_si, 0.980665);
  EXPECT_NEAR(test::provenance(*r.program, "texture.orientation").value_si, M_PI / 2, 1e-15);
  EXPECT_DOUBLE_EQ(r.program->max_lateral_force_N, 0.980665);
}

TEST(Units, NumberWithoutUnitIsAnError) {
  auto r = test::shipped_compiler().compile_text("grating period 2.5 amplitude 1 N");
  EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0203"});
  EXPECT_FALSE(r.program);
}

TEST(Units, UnitOfTheWrongDimensionIsAnError) {
  auto r = test::shipped_compiler().compile_text("grating period 2.5 N amplitude 1 N");
  ASSERT_EQ(test::codes(r), std::vector<std::string>{"E0205"});
  EXPECT_NE(r.diagnostics.all()[0].message.find("force unit"), std::string::npos);
  EXPECT_NE(r.diagnostics.all()[0].suggestion.find("mm"), std::string::npos);
}

TEST(Units, UnknownUnitSuggestsTheClosest) {
  auto r = test::shipped_compiler().compile_text("spring 200 N/mn");
  ASSERT_EQ(test::codes(r), std::vector<std::string>{"E0204"});
  EXPECT_EQ(r.diagnostics.all()[0].suggestion, "did you mean `N/mm`?");
}

TEST(Units, RoughnessTakesNoUnit) {
  auto r = test::shipped_compiler().compile_text("grating period 2 mm; roughness 0.5 N");
  EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0205"});
}
