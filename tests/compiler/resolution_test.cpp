// Layer resolution: representative, then perceptual, then physical; the file beats what it
// inherits; one statement per quantity in a file.
#include <algorithm>
#include <fstream>

#include <gtest/gtest.h>

#include "test_support.hpp"

using namespace sandpaper;
using compiler::Severity;
using test::provenance;

TEST(Resolution, LibraryEntryIsInheritedWhole) {
  auto r = test::shipped_compiler().compile_text("corduroy");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const auto& p = *r.program;
  // library/textiles/corduroy.hmat: grating period 3.2 mm hill 60%, roughness 0.45.
  EXPECT_DOUBLE_EQ(provenance(p, "texture.period").value_si, 0.0032);
  EXPECT_EQ(provenance(p, "texture.period").layer, "representative");
  EXPECT_NE(provenance(p, "texture.period").source.find("library corduroy"), std::string::npos);
  EXPECT_DOUBLE_EQ(provenance(p, "texture.hill").value_si, 0.6);
  EXPECT_NEAR(p.max_lateral_force_N, test::expected_force_for_roughness(0.45), 1e-9);
  EXPECT_NEAR(p.roughness, 0.45, 1e-12);
  EXPECT_EQ(p.describes, "wide-wale cotton corduroy, ribs across the stroke");
}

TEST(Resolution, FileBeatsInheritedParameterByParameter) {
  auto r = test::shipped_compiler().compile_text("like corduroy; grating period 2 mm");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const auto& p = *r.program;
  EXPECT_DOUBLE_EQ(provenance(p, "texture.period").value_si, 0.002);
  EXPECT_EQ(provenance(p, "texture.period").layer, "physical");
  EXPECT_DOUBLE_EQ(provenance(p, "texture.hill").value_si, 0.6);  // not stated: inherited
  EXPECT_EQ(provenance(p, "texture.hill").layer, "representative");
  EXPECT_NEAR(p.roughness, 0.45, 1e-12);  // force still from the library's roughness
}

// LANGUAGE.md: a grating statement overrides the inherited grating parameter by parameter, so it
// may leave out the period too (issue 15: "like corduroy; grating hill 40%" was E0201).
TEST(Resolution, GratingWithoutPeriodOverridesOnlyWhatItSays) {
  auto r = test::shipped_compiler().compile_text("like corduroy; grating hill 40%");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_DOUBLE_EQ(provenance(*r.program, "texture.hill").value_si, 0.4);
  EXPECT_EQ(provenance(*r.program, "texture.hill").layer, "physical");
  EXPECT_DOUBLE_EQ(provenance(*r.program, "texture.period").value_si, 0.0032);  // corduroy's
  EXPECT_EQ(provenance(*r.program, "texture.period").layer, "representative");
  // Nothing to inherit a period from: one error at the statement, saying what to write.
  auto none = test::shipped_compiler().compile_text("grating hill 40%; roughness 0.5");
  EXPECT_EQ(test::codes(none), std::vector<std::string>{"E0315"});
  EXPECT_NE(compiler::format_diagnostics(none.diagnostics).find("grating period 2.5 mm"), std::string::npos);
  // A bare `grating` still asks for its options.
  EXPECT_EQ(test::codes(test::shipped_compiler().compile_text("grating; roughness 0.5")), std::vector<std::string>{"E0216"});
}

TEST(Resolution, AnEmptyMaterialIsAnErrorAndNothingIsSaidWithForceNothing) {
  for (const char* text : {"", "  \n", "# only a comment\n", "material \"blank\" {\n}\n"}) {
    auto r = test::shipped_compiler().compile_text(text);
    EXPECT_FALSE(r.ok()) << text;
    EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0316"}) << text;
    EXPECT_FALSE(r.program) << "a failed compile's output is never used";
  }
  // Meaning nothing on purpose compiles, with the warning that it feels like nothing.
  auto nothing = test::shipped_compiler().compile_text("force Nothing");
  ASSERT_TRUE(nothing.ok()) << compiler::format_diagnostics(nothing.diagnostics);
  auto spring = test::shipped_compiler().compile_text("spring 200 N/m");
  EXPECT_TRUE(spring.ok());
}

// A missing image is reported alone: not after a warning about how its roughness would extrapolate.
TEST(Resolution, MissingImageReportsOnlyItsError) {
  auto r = test::shipped_compiler().compile_text("heightmap \"no-such-image.png\" size 50 mm; roughness 0.5");
  EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0401"});
  EXPECT_TRUE(test::codes(r, Severity::Warning).empty()) << compiler::format_diagnostics(r.diagnostics);
}

// An unnamed one-line description that changes its library entry is not named as the entry itself.
TEST(Resolution, ModifiedEntryIsNotNamedAsTheEntry) {
  auto r = test::shipped_compiler().compile_text("like corduroy; roughness 0.7");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.program->name, "like corduroy; roughness 0.7");
  EXPECT_EQ(test::shipped_compiler().compile_text("corduroy").program->name, "corduroy");
  EXPECT_EQ(test::shipped_compiler().compile_text("like corduroy").program->name, "corduroy");
}

TEST(Resolution, PerceptualInFileBeatsInheritedPhysical) {
  // a10p25 states a physical amplitude (400 ju, Table 8); this file's roughness replaces it.
  auto r = test::shipped_compiler().compile_text("like a10p25; roughness 0.3");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_NEAR(r.program->max_lateral_force_N, test::expected_force_for_roughness(0.3), 1e-9);
  EXPECT_EQ(provenance(*r.program, "texture.max_lateral_force").layer, "perceptual");
  auto base = test::shipped_compiler().compile_text("a10p25");
  ASSERT_TRUE(base.ok());
  EXPECT_NEAR(base.program->max_lateral_force_N, 400 * 0.490909 * 0.00980665, 1e-9);  // 400 ju of 0.490909 gf
}

TEST(Resolution, PhysicalAmplitudeInFileBeatsInheritedRoughness) {
  auto r = test::shipped_compiler().compile_text("like corduroy; grating period 3 mm amplitude 50 gf");
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.program->max_lateral_force_N, 0.4903325, 1e-12);
  EXPECT_EQ(provenance(*r.program, "texture.max_lateral_force").layer, "physical");
}

TEST(Resolution, RoughnessLevelByName) {
  auto r = test::shipped_compiler().compile_text("grating period 2 mm; roughness coarse");
  ASSERT_TRUE(r.ok());
  // calibration/levels/roughness-levels.toml: coarse = 0.5598 (178 gf).
  EXPECT_NEAR(r.program->roughness, 0.5598, 1e-12);
  EXPECT_NEAR(r.program->max_lateral_force_N, 178 * 9.80665e-3, 0.01);
  auto bad = test::shipped_compiler().compile_text("grating period 2 mm; roughness corse");
  ASSERT_EQ(test::codes(bad), std::vector<std::string>{"E0307"});
  EXPECT_EQ(bad.diagnostics.all()[0].suggestion, "did you mean `coarse`?");
}

TEST(Resolution, SameQuantityTwiceInOneFileNamesBothLines) {
  auto dir = test::temp_dir("conflict");
  std::ofstream(dir + "/m.hmat") << "material \"m\" {\n  grating period 2 mm\n  roughness 0.5\n  spring 10 N/m\n"
                                    "  grating period 3 mm amplitude 1 N\n}\n";
  auto r = test::shipped_compiler().compile_file(dir + "/m.hmat");
  ASSERT_EQ(test::codes(r), (std::vector<std::string>{"E0302", "E0302"}));
  const auto& texture = r.diagnostics.all()[0];
  EXPECT_EQ(texture.location.line, 5);
  ASSERT_EQ(texture.notes.size(), 1u);
  EXPECT_EQ(texture.notes[0].location.line, 2);
  EXPECT_NE(texture.message.find("the texture"), std::string::npos);
  const auto& force = r.diagnostics.all()[1];
  EXPECT_EQ(force.location.line, 5);
  EXPECT_EQ(force.notes[0].location.line, 3);
  EXPECT_NE(force.message.find("maximum lateral force"), std::string::npos);
  EXPECT_FALSE(r.program);
}

TEST(Resolution, UnknownLibraryEntrySuggests) {
  auto r = test::shipped_compiler().compile_text("like corduroi");
  ASSERT_EQ(test::codes(r), std::vector<std::string>{"E0301"});
  EXPECT_EQ(r.diagnostics.all()[0].suggestion, "did you mean `corduroy`?");
  auto bare = test::shipped_compiler().compile_text("unobtainium");
  EXPECT_EQ(test::codes(bare), std::vector<std::string>{"E0301"});
}

TEST(Resolution, LibraryCycleIsCaught) {
  auto dir = test::temp_dir("cycle");
  std::ofstream(dir + "/a.hmat") << "like b\n";
  std::ofstream(dir + "/b.hmat") << "like a\n";
  compiler::CompileOptions o;
  o.library_dir = dir;
  o.calibration_dir = std::string(SANDPAPER_SOURCE_DIR) + "/calibration";
  compiler::Compiler c(o);
  auto r = c.compile_text("a");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(test::codes(r)[0], "E0306");
  bool cycle = false;
  for (const auto& n : r.diagnostics.all()[0].notes) cycle |= n.message.find("cycle") != std::string::npos;
  EXPECT_TRUE(cycle);
}

// The warnings of `r` but W0350 (felt at speed), which a fine float grating also gets and which
// tests/e2e/felt_at_speed_test.cpp tests.
std::vector<std::string> warnings_but_speed(const compiler::CompileResult& r) {
  auto w = test::codes(r, Severity::Warning);
  w.erase(std::remove(w.begin(), w.end(), "W0350"), w.end());
  return w;
}

TEST(Resolution, RoughnessAboveOneNeedsExtrapolate) {
  auto r = test::shipped_compiler().compile_text("grating period 2 mm; roughness 1.2");
  EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0303"});
  auto ok = test::shipped_compiler().compile_text("grating period 2 mm; extrapolate; roughness 1.2");
  ASSERT_TRUE(ok.ok());
  EXPECT_EQ(warnings_but_speed(ok), std::vector<std::string>{"W0303"});
  EXPECT_NEAR(ok.program->max_lateral_force_N, test::expected_force_for_roughness(1.2), 1e-9);
}

TEST(Resolution, ExtrapolationWarnings) {
  auto weak = test::shipped_compiler().compile_text("grating period 2 mm; roughness 0.05");
  ASSERT_TRUE(weak.ok());
  EXPECT_EQ(warnings_but_speed(weak), std::vector<std::string>{"W0301"});
  auto edge = test::shipped_compiler().compile_text("grating period 2 mm; roughness 0.0983");
  EXPECT_TRUE(warnings_but_speed(edge).empty());
  auto fine = test::shipped_compiler().compile_text("grating period 0.5 mm; roughness 0.5");
  EXPECT_EQ(warnings_but_speed(fine), std::vector<std::string>{"W0302"});
  auto wide = test::shipped_compiler().compile_text("grating period 12 mm; roughness 0.5");
  EXPECT_EQ(warnings_but_speed(wide), std::vector<std::string>{"W0302"});
  auto inside = test::shipped_compiler().compile_text("grating period 10 mm; roughness 0.5");
  EXPECT_TRUE(test::codes(inside, Severity::Warning).empty());
  // Warnings travel in the patch program too.
  ASSERT_FALSE(fine.program->warnings.empty());
  EXPECT_EQ(fine.program->warnings[0].code, "W0302");
}

TEST(Resolution, TextureNeedsAForce) {
  auto r = test::shipped_compiler().compile_text("grating period 2 mm");
  EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0308"});
  // With no reference texture in the library, a roughness has nothing to set.
  compiler::CompileOptions bare;
  bare.library_dir = SANDPAPER_SOURCE_DIR "/tests/compiler/data/library-without-manifest";
  compiler::Compiler bare_library(bare);
  auto orphan = bare_library.compile_text("roughness 0.4; spring 10 N/m");
  EXPECT_EQ(test::codes(orphan), std::vector<std::string>{"E0309"});
}

TEST(Resolution, OutOfRangeValues) {
  EXPECT_EQ(test::codes(test::shipped_compiler().compile_text("grating period -2 mm amplitude 1 N")),
            std::vector<std::string>{"E0304"});
  EXPECT_EQ(test::codes(test::shipped_compiler().compile_text("grating period 2 mm hill 100% amplitude 1 N")),
            std::vector<std::string>{"E0304"});
  EXPECT_EQ(test::codes(test::shipped_compiler().compile_text("damper -1 N*s/m")), std::vector<std::string>{"E0304"});
  EXPECT_EQ(test::codes(test::shipped_compiler().compile_text("grating period 2 mm; roughness -0.1")),
            std::vector<std::string>{"E0304"});
}

TEST(Resolution, DeviceMaximumForceIsAnErrorThatSaysTheBestReachable) {
  auto r = test::shipped_compiler().compile_text("grating period 2 mm amplitude 12 N");
  ASSERT_EQ(test::codes(r), std::vector<std::string>{"E0310"});
  // sim reaches 10 N: roughness (10 / 3.746)^0.7596 = 2.108, shown rounded down so it stays reachable.
  EXPECT_NE(r.diagnostics.all()[0].suggestion.find("reaches roughness 2.1 at most"), std::string::npos)
      << r.diagnostics.all()[0].suggestion;
}

TEST(Resolution, UnknownDeviceIsRefused) {
  compiler::CompileOptions o;
  o.device = "phantom";
  o.calibration_dir = std::string(SANDPAPER_SOURCE_DIR) + "/calibration";
  EXPECT_THROW(compiler::Compiler{o}, std::invalid_argument);
}

TEST(Resolution, EveryLibraryEntryCompilesAndSaysWhereItsNumbersComeFrom) {
  const auto& c = test::shipped_compiler();
  const auto& entries = c.library().entries();
  EXPECT_GE(entries.size(), 60u);  // issue 6: at least 60 entries
  for (const auto& e : entries) {
    auto r = c.compile_text(e.name);
    EXPECT_TRUE(r.ok()) << e.name << "\n" << compiler::format_diagnostics(r.diagnostics);
    if (r.ok()) {
      EXPECT_FALSE(r.program->describes.empty()) << e.name;
      // The thesis' Nothing stimulus (4.3, the no-force control of Ch. 4) plays nothing on purpose;
      // every other entry must play something.
      const bool thesis_nothing = e.likes == std::vector<std::string>{"Nothing"};
      EXPECT_NE(r.program->terms.empty(), !thesis_nothing) << e.name << ": an entry that plays nothing";
    }
    for (const auto& st : e.syntax.statements) {
      if (!compiler::carries_numbers(st)) continue;
      EXPECT_FALSE(st.sources.empty()) << e.relative_path << ":" << st.location.line << ": `" << st.text
                                       << "` has no `source` statement";
    }
  }
}
