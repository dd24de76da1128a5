// A material's numbers as sliders (compiler/parameters.hpp): found in statements only, with their
// units and ranges; an edit changes only the number's characters, so comments and layout survive.
#include <cmath>

#include <gtest/gtest.h>

#include "sandpaper/compiler/parameters.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {

using compiler::Parameter;

const Parameter& find(const std::vector<Parameter>& ps, const std::string& name) {
  for (const auto& p : ps)
    if (p.name == name) return p;
  ADD_FAILURE() << "no parameter " << name;
  static Parameter none;
  return none;
}

constexpr const char* kCorduroy = R"(# A comment that says 2.5 mm and roughness 9
material "c" {
  roughness 0.55      # perceptual, 0.55 stays in this comment
  grating period 3.2 mm hill 50%   # physical
}
)";

TEST(Parameters, ListsEveryNumberOfTheStatementsWithItsUnitAndPlace) {
  const auto& cal = test::shipped_compiler().calibration();
  const auto ps = compiler::material_parameters(kCorduroy, cal, 10);
  ASSERT_EQ(ps.size(), 3u);  // not the numbers in comments
  const auto& r = find(ps, "roughness");
  EXPECT_EQ(r.layer, "perceptual");
  EXPECT_DOUBLE_EQ(r.value, 0.55);
  EXPECT_EQ(r.line, 3);
  EXPECT_EQ(r.column, 13);
  EXPECT_EQ(r.length, 4);
  // Roughness spans the compile map's calibrated stimuli: Figure 19's weakest and strongest forces.
  const auto& map = cal.roughness_map();
  // (widened to whole slider steps)
  EXPECT_LE(r.min, map.percept_of(map.force->min));
  EXPECT_GT(r.min, map.percept_of(map.force->min) - r.step);
  EXPECT_GE(r.max, map.percept_of(map.force->max));
  EXPECT_LT(r.max, map.percept_of(map.force->max) + r.step);
  const auto& period = find(ps, "grating.period");
  EXPECT_EQ(period.unit, "mm");
  EXPECT_DOUBLE_EQ(period.value, 3.2);
  EXPECT_NEAR(period.si, 3.2e-3, 1e-15);
  EXPECT_DOUBLE_EQ(period.min, 0.3);
  EXPECT_DOUBLE_EQ(period.max, 20);
  const auto& hill = find(ps, "grating.hill");
  EXPECT_EQ(hill.unit, "%");
  EXPECT_DOUBLE_EQ(hill.max, 100);
}

TEST(Parameters, AnEditChangesOnlyTheNumbersCharacters) {
  const auto& cal = test::shipped_compiler().calibration();
  const auto ps = compiler::material_parameters(kCorduroy, cal, 10);
  const std::string edited = compiler::set_parameter(kCorduroy, ps, "grating.period", 5, "mm");
  std::string expected = kCorduroy;
  expected.replace(expected.find("3.2 mm"), 3, "5");
  EXPECT_EQ(edited, expected);
  // Another unit of the same dimension is converted to the one written.
  EXPECT_NE(compiler::set_parameter(kCorduroy, ps, "grating.period", 0.0045, "m").find("period 4.5 mm"), std::string::npos);
  const std::string rough = compiler::set_parameter(kCorduroy, ps, "roughness", 0.7);
  EXPECT_NE(rough.find("roughness 0.7      # perceptual, 0.55 stays"), std::string::npos);
  // The edited text compiles to the new number.
  const auto r = test::shipped_compiler().compile_text(edited, "edited.hmat");
  ASSERT_TRUE(r.ok());
}

TEST(Parameters, RefusesUnknownNamesWrongDimensionsAndNonFiniteValues) {
  const auto& cal = test::shipped_compiler().calibration();
  const auto ps = compiler::material_parameters(kCorduroy, cal, 10);
  EXPECT_THROW(compiler::set_parameter(kCorduroy, ps, "grating.pitch", 1), compiler::ParameterError);
  EXPECT_THROW(compiler::set_parameter(kCorduroy, ps, "grating.period", 1, "N"), compiler::ParameterError);
  EXPECT_THROW(compiler::set_parameter(kCorduroy, ps, "grating.period", 1, "furlong"), compiler::ParameterError);
  EXPECT_THROW(compiler::set_parameter(kCorduroy, ps, "grating.period", std::nan("")), compiler::ParameterError);
  EXPECT_THROW(compiler::set_parameter(kCorduroy, ps, "roughness", 0.5, "mm"), compiler::ParameterError);
}

TEST(Parameters, ForceLawArgumentsAndSecondStatementsGetTheirOwnNames) {
  const std::string text = "force Wave amplitude 0.3 N period 4 mm\nspring 80 N/m\nspring 90 N/m\n";
  const auto ps = compiler::material_parameters(text, test::shipped_compiler().calibration(), 10);
  EXPECT_DOUBLE_EQ(find(ps, "force.Wave.amplitude").value, 0.3);
  EXPECT_DOUBLE_EQ(find(ps, "force.Wave.period").value, 4);
  EXPECT_DOUBLE_EQ(find(ps, "spring.stiffness").value, 80);
  EXPECT_DOUBLE_EQ(find(ps, "spring.stiffness#2").value, 90);
}

TEST(Parameters, FormatsSliderValuesShortAndWithoutExponents) {
  EXPECT_EQ(compiler::format_parameter_value(3.0), "3");
  EXPECT_EQ(compiler::format_parameter_value(2.55), "2.55");
  EXPECT_EQ(compiler::format_parameter_value(0.0000125), "0.0000125");
  EXPECT_EQ(compiler::format_parameter_value(0.1 + 0.2), "0.3");
}

constexpr const char* kWorkspace = R"(workspace "w" {
  size 200 mm x 200 mm   # the area
  patch "corduroy" at -40 mm, 0 mm size 30 mm x 60 mm   # left
  patch "roughness 0.3; grating period 5 mm" at 40 mm, 0 mm
}
)";

TEST(Parameters, WorkspacePatchesMoveAndResizeInTheirOwnText) {
  const auto ps = compiler::workspace_parameters(kWorkspace);
  EXPECT_DOUBLE_EQ(find(ps, "patch.0.x").value, -40);
  EXPECT_DOUBLE_EQ(find(ps, "patch.0.height").value, 60);
  EXPECT_DOUBLE_EQ(find(ps, "patch.1.y").value, 0);
  std::string moved = compiler::place_workspace_patch(kWorkspace, 0, -35.5, 10, 30, 40);
  EXPECT_NE(moved.find("patch \"corduroy\" at -35.5 mm, 10 mm size 30 mm x 40 mm   # left"), std::string::npos) << moved;
  // A patch that took its material's size gains a `size` clause.
  moved = compiler::place_workspace_patch(kWorkspace, 1, 50, -5, 20, 25);
  EXPECT_NE(moved.find("at 50 mm, -5 mm size 20 mm x 25 mm\n"), std::string::npos) << moved;
  EXPECT_NE(moved.find("# the area"), std::string::npos);
  EXPECT_THROW(compiler::place_workspace_patch(kWorkspace, 2, 0, 0, 1, 1), compiler::ParameterError);
  EXPECT_THROW(compiler::place_workspace_patch(kWorkspace, 0, 0, 0, -1, 1), compiler::ParameterError);
}

}  // namespace
}  // namespace sandpaper
