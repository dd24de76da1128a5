// W0503 and the roughness order of a workspace: materials whose maximum lateral forces differ by
// less than one force JND (Minsky 1995 5.4.2; calibration/knowledge/force-jnd.toml) feel equally
// rough. Forces are chosen from the loaded JND data, not from constants.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "sandpaper/compiler/workspace.hpp"
#include "sandpaper/schema/units.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {

compiler::WorkspaceResult compile(const std::string& text) {
  return compiler::compile_workspace_text(test::shipped_compiler(), text, "<test.hws>", ".");
}

const calibration::ForceJndData& jnd() { return test::shipped_compiler().calibration().knowledge().force_jnd; }

// Two gratings of forces f1 and f2 (N), written in gf, side by side.
std::string two_patches(double f1, double f2, const char* period2 = "2 mm") {
  const double gf = schema::find_unit("gf")->to_si;
  std::ostringstream os;
  os.precision(10);
  os << "workspace \"jnd\" {\n"
     << "  patch \"grating period 2 mm amplitude " << f1 / gf << " gf\" at -30 mm, 0 mm size 40 mm\n"
     << "  patch \"grating period " << period2 << " amplitude " << f2 / gf << " gf\" at 30 mm, 0 mm size 40 mm\n"
     << "}\n";
  return os.str();
}

std::vector<const compiler::Diagnostic*> warnings(const compiler::WorkspaceResult& r, const std::string& code) {
  std::vector<const compiler::Diagnostic*> out;
  for (const auto& d : r.diagnostics.all())
    if (d.code == code) out.push_back(&d);
  return out;
}

TEST(WorkspaceJnd, TwoPatchesWithinOneJndWarnNamingBothForcesAndTheJnd) {
  const double f1 = 1.0, f2 = f1 * std::pow(1 + jnd().weber_fraction, 0.5);  // half a JND apart
  auto r = compile(two_patches(f1, f2));
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  auto w = warnings(r, "W0503");
  ASSERT_EQ(w.size(), 1u) << compiler::format_diagnostics(r.diagnostics);
  const auto& m = w[0]->message;
  EXPECT_NE(m.find("patch 2"), std::string::npos) << m;
  EXPECT_NE(m.find("patch 1"), std::string::npos) << m;
  EXPECT_NE(m.find("1 N"), std::string::npos) << m;
  EXPECT_NE(m.find("1.061 N"), std::string::npos) << m;
  EXPECT_NE(m.find("differ by 0.5 force JND"), std::string::npos) << m;
  EXPECT_NE(m.find("one JND at 1 N is 0.125 N"), std::string::npos) << m;
  EXPECT_NE(m.find(jnd().file), std::string::npos) << "names the JND's source: " << m;
  EXPECT_NE(m.find("tan1992"), std::string::npos) << m;
  EXPECT_EQ(w[0]->location.line, 3);
  ASSERT_EQ(w[0]->notes.size(), 1u);
  EXPECT_EQ(w[0]->notes[0].location.line, 2);
}

TEST(WorkspaceJnd, PatchesThreeJndsApartOrEqualDoNotWarn) {
  // Table 8's workspaces used force levels far more than a JND apart.
  auto apart = compile(two_patches(1.0, std::pow(1 + jnd().weber_fraction, 3.0)));
  ASSERT_TRUE(apart.ok());
  EXPECT_TRUE(warnings(apart, "W0503").empty()) << compiler::format_diagnostics(apart.diagnostics);
  // Just over one JND: no warning; just under: a warning.
  EXPECT_TRUE(warnings(compile(two_patches(1.0, (1 + jnd().weber_fraction) * 1.001)), "W0503").empty());
  EXPECT_EQ(warnings(compile(two_patches(1.0, (1 + jnd().weber_fraction) * 0.999)), "W0503").size(), 1u);
  // The same force at another period is the same roughness on purpose (Figure 20: period adds nothing).
  auto same = compile(two_patches(1.0, 1.0, "5 mm"));
  ASSERT_TRUE(same.ok());
  EXPECT_TRUE(warnings(same, "W0503").empty());
  // One material on two patches is not two materials.
  auto twice = compile("workspace \"w\" {\n  patch \"corduroy\" at -30 mm, 0 mm size 40 mm\n"
                       "  patch \"corduroy\" at 30 mm, 0 mm size 40 mm\n}\n");
  EXPECT_TRUE(warnings(twice, "W0503").empty());
}

// No workspace warning (W05xx: hidden patches, JND collisions); the materials' own warnings (W0350 for
// the fine gratings at 100 mm/s) are the materials' business.
TEST(WorkspaceJnd, ShippedExamplesHaveNoWorkspaceWarnings) {
  for (const char* f : {"examples/workspace/sampler.hws", "examples/workspace/cloths.hws", "examples/workspace/periods.hws"}) {
    auto r = compiler::compile_workspace_file(test::shipped_compiler(), f);
    ASSERT_TRUE(r.ok()) << f;
    for (const auto& d : r.diagnostics.all())
      EXPECT_TRUE(d.code.rfind("W05", 0) != 0 && d.severity != compiler::Severity::Error)
          << f << "\n" << compiler::format_diagnostics(r.diagnostics);
  }
}

TEST(WorkspaceJnd, RoughnessOrderListsJndStepsBetweenNeighbours) {
  auto r = compiler::compile_workspace_file(test::shipped_compiler(), "examples/workspace/sampler.hws");
  ASSERT_TRUE(r.ok());
  auto order = compiler::roughness_order(*r.program, jnd());
  ASSERT_EQ(order.size(), 7u);
  for (std::size_t i = 0; i + 1 < order.size(); ++i) {
    EXPECT_LE(order[i].force_N, order[i + 1].force_N);
    EXPECT_NEAR(order[i].jnd_to_next, std::log(order[i + 1].force_N / order[i].force_N) / std::log1p(jnd().weber_fraction), 1e-9);
    EXPECT_GE(order[i].jnd_to_next, 1) << order[i].material << " and " << order[i + 1].material;
  }
  EXPECT_EQ(order.back().jnd_to_next, 0);
  EXPECT_EQ(order.front().material, "silk-satin");
  // Patches with the same material text are one entry.
  auto p = compiler::compile_workspace_file(test::shipped_compiler(), "examples/workspace/periods.hws");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(compiler::roughness_order(*p.program, jnd()).size(), 5u);
}

}  // namespace
}  // namespace sandpaper
