// The perceptual words besides roughness (issue 4): viscosity/stickiness, slipperiness,
// softness/springiness and bumpiness, each through its provisional map in calibration/maps/.
// Resolution is checked against the map read here from its own file (calibration::load_map_file)
// and against the law restated from the file's comments; every use of a provisional map must warn
// W0320 in the diagnostics, the program's warnings, the JSON and explain.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "sandpaper/compiler/explain.hpp"
#include "sandpaper/schema/patch_json.hpp"
#include "test_support.hpp"

using namespace sandpaper;
using compiler::Severity;
using test::provenance;
namespace fs = std::filesystem;

namespace {

calibration::PsychophysicalMap map_file(const std::string& id) {
  return calibration::load_map_file(std::string(SANDPAPER_SOURCE_DIR) + "/calibration/maps/" + id + ".toml");
}

compiler::CompileResult compile(const std::string& text) { return test::shipped_compiler().compile_text(text); }

std::size_t count(const std::vector<std::string>& xs, const std::string& x) {
  return static_cast<std::size_t>(std::count(xs.begin(), xs.end(), x));
}

struct Word {
  const char* word;
  const char* map;        // map id
  const char* parameter;  // provenance name of what it sets
  const char* target;     // provenance name of the ratio-scale target
};
const Word kWords[] = {
    {"viscosity", "stevens-guirao1964", "damper.damping", "damper.viscosity_target"},
    {"stickiness", "stevens-guirao1964", "damper.damping", "damper.viscosity_target"},
    {"slipperiness", "ekman1965", "friction.coefficient", "friction.slipperiness_target"},
    {"softness", "harper-stevens1964", "spring.stiffness", "spring.softness_target"},
    {"springiness", "harper-stevens1964", "spring.stiffness", "spring.softness_target"},
    {"bumpiness", "bumpiness-provisional", "texture.period", "texture.bumpiness_target"},
};

// A material text that compiles with `word value` (bumpiness needs a force for its grating).
std::string material(const Word& w, double value) {
  std::string text = std::string(w.word) + " " + std::to_string(value);
  if (std::string(w.word) == "bumpiness") text += "; roughness 0.4";
  return text;
}

}  // namespace

// Softness, viscosity and slipperiness compile through maps from the literature (sourced, each with
// a Weber fraction, each felt on real materials); bumpiness still through a provisional one.
TEST(PerceptMaps, ShippedCompileMapsAreSourcedExceptBumpiness) {
  const auto& cal = test::shipped_compiler().calibration();
  struct Expect { const char* percept; const char* id; bool provisional; double weber; };
  for (const Expect& e : {Expect{"viscosity", "stevens-guirao1964", false, 0.34}, Expect{"slipperiness", "ekman1965", false, 0.11},
                          Expect{"softness", "harper-stevens1964", false, 0.23}, Expect{"bumpiness", "bumpiness-provisional", true, 0}}) {
    SCOPED_TRACE(e.percept);
    const auto* m = cal.compile_map(e.percept);
    ASSERT_NE(m, nullptr);
    EXPECT_EQ(m->provisional, e.provisional);
    EXPECT_EQ(m->id, e.id);
    EXPECT_EQ(m->file, "calibration/maps/" + std::string(e.id) + ".toml");
    EXPECT_FALSE(m->citation.empty());
    EXPECT_EQ(m->real_material(), !e.provisional);
    if (e.weber > 0) EXPECT_DOUBLE_EQ(m->weber_fraction.value_or(0), e.weber);
    else EXPECT_FALSE(m->weber_fraction);
    // Percept 1 lies at one end of the map's domain: the ratio scale and the domain agree.
    const auto* d = m->damping ? &*m->damping : m->stiffness ? &*m->stiffness : m->period ? &*m->period
                  : m->friction ? &*m->friction : nullptr;
    ASSERT_NE(d, nullptr);
    EXPECT_NEAR(std::max(m->percept_of(d->min), m->percept_of(d->max)), 1.0, 1e-12);
  }
  EXPECT_FALSE(cal.roughness_map().provisional);
}

// The exponents and references, restated from the sources (Stevens and Guirao 1964: 0.42; Stevens's
// table, hardness 0.8 inverted; Ekman et al. 1965's bound -1 with Smith and Scott 1996's most
// slippery surface, 0.43; designed for bumpiness).
TEST(PerceptMaps, FilesStateTheDocumentedLaws) {
  struct Law { const char* id; double slope, reference_si; };
  for (const Law& l : {Law{"stevens-guirao1964", 0.42, 10.0}, Law{"harper-stevens1964", -0.8, 20.0},
                       Law{"ekman1965", -1.0, 0.43}, Law{"bumpiness-provisional", 0.5, 0.010}}) {
    SCOPED_TRACE(l.id);
    const auto m = map_file(l.id);
    EXPECT_DOUBLE_EQ(m.slope, l.slope);
    EXPECT_NEAR(m.reference_si, l.reference_si, 1e-12 * l.reference_si);
  }
  // The bumpiness map's anchor: the 2.5 mm transition of thesis 6.3.6 at bumpiness 0.5.
  EXPECT_NEAR(map_file("bumpiness-provisional").percept_of(0.0025), 0.5, 1e-12);
}

TEST(PerceptResolution, ValueBecomesTheParameterTheMapGives) {
  for (const Word& w : kWords) {
    const auto m = map_file(w.map);
    for (double value : {0.3, 0.5, 0.8, 1.0}) {
      SCOPED_TRACE(std::string(w.word) + " " + std::to_string(value));
      auto r = compile(material(w, value));
      ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
      const auto& pv = provenance(*r.program, w.parameter);
      EXPECT_NEAR(pv.value_si, m.value_for(value), 1e-12 * m.value_for(value));
      EXPECT_EQ(pv.layer, "perceptual");
      EXPECT_NEAR(provenance(*r.program, w.target).value_si, value, 1e-12);
    }
  }
}

TEST(PerceptResolution, NumbersAgreeWithTheLawsRestated) {
  auto v = compile("viscosity 0.5");
  ASSERT_TRUE(v.ok());
  EXPECT_NEAR(provenance(*v.program, "damper.damping").value_si, 10 * std::pow(0.5, 1 / 0.42), 1e-12);  // 1.92 N*s/m
  auto s = compile("softness 0.5");
  ASSERT_TRUE(s.ok());
  EXPECT_NEAR(provenance(*s.program, "spring.stiffness").value_si, 20 * std::pow(0.5, -1 / 0.8), 1e-9);  // 47.6 N/m
  auto b = compile("bumpiness 0.6; roughness 0.4");
  ASSERT_TRUE(b.ok());
  EXPECT_NEAR(provenance(*b.program, "texture.period").value_si, 0.0036, 1e-12);
  auto sl = compile("slipperiness 0.3");
  ASSERT_TRUE(sl.ok());
  EXPECT_NEAR(provenance(*sl.program, "friction.coefficient").value_si, 0.43 / 0.3, 1e-12);  // mu 1.43
  // One Coulomb friction term, holding and sliding alike, the hand pressing with 1 N.
  const schema::FrictionTerm* f = nullptr;
  for (const auto& t : sl.program->terms)
    if (const auto* x = std::get_if<schema::FrictionTerm>(&t)) f = x;
  ASSERT_NE(f, nullptr);
  EXPECT_NEAR(f->kinetic_coefficient, 0.43 / 0.3, 1e-12);
  EXPECT_DOUBLE_EQ(f->static_coefficient, f->kinetic_coefficient);
  EXPECT_DOUBLE_EQ(f->press_N, 1.0);
}

TEST(PerceptResolution, AliasesAreTheSameContinuum) {
  auto a = compile("viscosity 0.4"), b = compile("stickiness 0.4");
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_DOUBLE_EQ(provenance(*a.program, "damper.damping").value_si, provenance(*b.program, "damper.damping").value_si);
  auto c = compile("softness 0.4"), d = compile("springiness 0.4");
  ASSERT_TRUE(c.ok() && d.ok());
  EXPECT_DOUBLE_EQ(provenance(*c.program, "spring.stiffness").value_si,
                   provenance(*d.program, "spring.stiffness").value_si);
  // Softer is a weaker spring: the map's slope is negative.
  auto softer = compile("softness 0.8");
  ASSERT_TRUE(softer.ok());
  EXPECT_LT(provenance(*softer.program, "spring.stiffness").value_si, provenance(*c.program, "spring.stiffness").value_si);
}

// Slipperiness is scaled against the friction coefficient (Ekman et al. 1965; Smith and Scott 1996),
// so it compiles to Coulomb friction: passive, no energy bound, no W0306.
TEST(PerceptResolution, SlipperinessIsPassiveCoulombFriction) {
  auto r = compile("slipperiness 0.5");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  ASSERT_EQ(r.program->terms.size(), 1u);
  const auto* f = std::get_if<schema::FrictionTerm>(&r.program->terms[0]);
  ASSERT_NE(f, nullptr);
  EXPECT_NEAR(f->kinetic_coefficient, 0.86, 1e-12);  // 0.43 / 0.5
  EXPECT_TRUE(schema::is_passive(r.program->terms[0]));
  EXPECT_EQ(count(test::codes(r, Severity::Warning), "W0306"), 0u);
  EXPECT_NEAR(provenance(*r.program, "friction.press").value_si, 1.0, 1e-12);
  // slipperiness 0 would be an infinite coefficient.
  EXPECT_EQ(test::codes(compile("slipperiness 0")), std::vector<std::string>{"E0304"});
}

TEST(PerceptResolution, BumpinessSetsTheInheritedGratingsPeriodOnly) {
  // library/textiles/corduroy.hmat: grating period 3.2 mm hill 60%, roughness 0.45.
  auto r = compile("like corduroy; bumpiness 0.3");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_NEAR(provenance(*r.program, "texture.period").value_si, 0.010 * 0.09, 1e-12);
  EXPECT_EQ(provenance(*r.program, "texture.period").layer, "perceptual");
  EXPECT_DOUBLE_EQ(provenance(*r.program, "texture.hill").value_si, 0.6);
  EXPECT_EQ(provenance(*r.program, "texture.hill").layer, "representative");
  // Without a force the grating it makes has none: the same error as a grating statement.
  EXPECT_EQ(test::codes(compile("bumpiness 0.6")), std::vector<std::string>{"E0308"});
}

TEST(PerceptResolution, PhysicalStatementForTheSameParameterInOneFileIsAConflict) {
  for (const char* text : {"viscosity 0.4; damper 2 N*s/m", "stickiness 0.4; viscosity 0.3", "softness 0.5; spring 50 N/m",
                           "springiness 0.5; softness 0.5", "bumpiness 0.5; grating period 2 mm; roughness 0.3",
                           "bumpiness 0.5; pattern perlin feature 5 mm; roughness 0.3", "slipperiness 0.2; slipperiness 0.3"}) {
    SCOPED_TRACE(text);
    auto r = compile(text);
    EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0302"});
  }
  // A force law is a term of its own and sums with slipperiness, as with `damper` and `force Viscous`.
  EXPECT_TRUE(compile("slipperiness 0.2; force AntiViscous damping 1 N*s/m").ok());
}

TEST(PerceptResolution, FileBeatsWhatItInheritsEitherWay) {
  auto dir = test::temp_dir("percept-library");
  std::ofstream(dir + "/honey.hmat") << "material \"honey\" {\n  viscosity 0.8\n  softness 0.5\n}\n";
  compiler::CompileOptions o;
  o.library_dir = dir;
  o.calibration_dir = std::string(SANDPAPER_SOURCE_DIR) + "/calibration";
  compiler::Compiler c(o);
  const auto visc = map_file("stevens-guirao1964");

  // Inherited: the target and its warning come along, the provenance still names the map and file.
  auto inherited = c.compile_text("like honey");
  ASSERT_TRUE(inherited.ok()) << compiler::format_diagnostics(inherited.diagnostics);
  const auto& damping = provenance(*inherited.program, "damper.damping");
  EXPECT_NEAR(damping.value_si, visc.value_for(0.8), 1e-12);
  EXPECT_EQ(damping.layer, "representative");
  EXPECT_NE(damping.source.find("library honey"), std::string::npos) << damping.source;
  EXPECT_NE(damping.source.find("via stevens-guirao1964 (calibration/maps/stevens-guirao1964.toml)"),
            std::string::npos)
      << damping.source;
  EXPECT_EQ(count(test::codes(inherited, Severity::Warning), "W0321"), 2u);  // both maps' sources felt real materials
  EXPECT_EQ(count(test::codes(inherited, Severity::Warning), "W0320"), 0u);

  // The file's physical damper beats the inherited viscosity: no viscosity target, no viscosity warning.
  auto physical = c.compile_text("like honey; damper 2 N*s/m");
  ASSERT_TRUE(physical.ok());
  EXPECT_DOUBLE_EQ(provenance(*physical.program, "damper.damping").value_si, 2.0);
  EXPECT_EQ(provenance(*physical.program, "damper.damping").layer, "physical");
  for (const auto& pv : physical.program->provenance) EXPECT_NE(pv.parameter, "damper.viscosity_target");
  EXPECT_EQ(count(test::codes(physical, Severity::Warning), "W0321"), 1u);  // softness is still inherited
}

TEST(PerceptResolution, FilesViscosityBeatsInheritedDamper) {
  // library/textiles/silk-satin.hmat states damper 0.5 N*s/m.
  auto r = compile("like silk-satin; viscosity 0.2");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_NEAR(provenance(*r.program, "damper.damping").value_si, map_file("stevens-guirao1964").value_for(0.2), 1e-12);
  EXPECT_EQ(provenance(*r.program, "damper.damping").layer, "perceptual");
}

TEST(PerceptDiagnostics, OutOfRangeValuesAreErrorsThatSayWhatToWrite) {
  struct Case { const char* text; const char* code; const char* in_message; };
  for (const Case& c : {Case{"viscosity -0.2", "E0304", "negative"}, Case{"softness 0", "E0304", "infinitely stiff"},
                        Case{"bumpiness 0; roughness 0.3", "E0304", "period 0"},
                        Case{"viscosity 1.2", "E0303", "top of the stevens-guirao1964 map's domain"},
                        Case{"slipperiness 2", "E0303", "above 1"}, Case{"softness 1.5", "E0303", "above 1"},
                        Case{"viscosity thik", "E0307", "unknown viscosity level"},
                        Case{"springiness 0.5 N/m", "E0205", "takes no unit"}, Case{"viscosty 0.4", "E0202", "viscosty"}}) {
    SCOPED_TRACE(c.text);
    auto r = compile(c.text);
    ASSERT_EQ(test::codes(r), std::vector<std::string>{c.code}) << compiler::format_diagnostics(r.diagnostics);
    EXPECT_NE(r.diagnostics.all()[0].message.find(c.in_message), std::string::npos) << r.diagnostics.all()[0].message;
    EXPECT_FALSE(r.diagnostics.all()[0].suggestion.empty());
  }
  EXPECT_EQ(compile("viscosty 0.4").diagnostics.all()[0].suggestion, "did you mean `viscosity`?");
  EXPECT_EQ(compile("slipperyness 0.4").diagnostics.all()[0].suggestion, "did you mean `slipperiness`?");
  // Zero damping is allowed: no damper force.
  auto zero = compile("viscosity 0");
  ASSERT_TRUE(zero.ok());
  EXPECT_DOUBLE_EQ(provenance(*zero.program, "damper.damping").value_si, 0.0);
}

TEST(PerceptDiagnostics, ExtrapolationWarns) {
  auto above = compile("viscosity 1.2; extrapolate");
  ASSERT_TRUE(above.ok());
  EXPECT_EQ(count(test::codes(above, Severity::Warning), "W0303"), 1u);
  EXPECT_NEAR(provenance(*above.program, "damper.damping").value_si, 10 * std::pow(1.2, 1 / 0.42), 1e-9);
  // Below the domain: softness 0.1 is a spring stiffer than the map's 200 N/m.
  auto below = compile("softness 0.1");
  ASSERT_TRUE(below.ok());
  EXPECT_EQ(count(test::codes(below, Severity::Warning), "W0301"), 1u);
  auto inside = compile("softness 0.5");
  ASSERT_TRUE(inside.ok());
  EXPECT_EQ(count(test::codes(inside, Severity::Warning), "W0301"), 0u);
}

// A provisional map (bumpiness) warns W0320; a sourced map whose subjects felt real materials
// (softness, viscosity, slipperiness) warns W0321 instead; each in every output, naming the map.
TEST(PerceptWarnings, EveryProvisionalOrRealMaterialMapWarnsInEveryOutput) {
  const auto& c = test::shipped_compiler();
  for (const Word& w : kWords) {
    SCOPED_TRACE(w.word);
    auto r = compile(material(w, 0.5));
    ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
    const std::string file = std::string("calibration/maps/") + w.map + ".toml";
    const bool provisional = c.calibration().find_map(w.map)->provisional;
    const std::string code = provisional ? "W0320" : "W0321", other = provisional ? "W0321" : "W0320";
    // Diagnostics (what `compile` prints on stderr).
    ASSERT_EQ(count(test::codes(r, Severity::Warning), code), 1u);
    EXPECT_EQ(count(test::codes(r, Severity::Warning), other), 0u);
    for (const auto& d : r.diagnostics.all())
      if (d.code == code) {
        if (provisional) EXPECT_NE(d.message.find(std::string("provisional map ") + w.map), std::string::npos) << d.message;
        else EXPECT_NE(d.message.find("real materials"), std::string::npos) << d.message;
        EXPECT_NE(d.message.find(file), std::string::npos) << d.message;
      }
    // The patch program's warnings, and so `compile --json`, `inspect` and `run`.
    bool in_program = false;
    for (const auto& pw : r.program->warnings) in_program |= pw.code == code && pw.message.find(w.map) != std::string::npos;
    EXPECT_TRUE(in_program);
    EXPECT_NE(schema::to_json(*r.program).dump().find(code), std::string::npos);
    // explain's text: the warning, and the map named beside the percept with its source and domain.
    const auto text = compiler::explain_text(*r.material, *r.program, c.calibration(), c.device());
    EXPECT_NE(text.find(code), std::string::npos);
    EXPECT_NE(text.find(std::string(provisional ? "PROVISIONAL map " : "calibration ") + w.map + ", " + file), std::string::npos) << text;
    EXPECT_NE(text.find("source: " + c.calibration().find_map(w.map)->citation), std::string::npos) << text;
    EXPECT_NE(text.find("domain: "), std::string::npos) << text;
    // Provenance names the map and its file.
    EXPECT_NE(provenance(*r.program, w.parameter).source.find(std::string("via ") + w.map + " (" + file + ")"),
              std::string::npos);
  }
}

TEST(PerceptWarnings, RoughnessAloneDoesNotWarnProvisional) {
  auto r = compile("grating period 2 mm; roughness 0.5");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(count(test::codes(r, Severity::Warning), "W0320"), 0u);
  for (const auto& w : r.program->warnings) EXPECT_NE(w.code, "W0320");
  const auto& c = test::shipped_compiler();
  EXPECT_EQ(compiler::explain_text(*r.material, *r.program, c.calibration(), c.device()).find("PROVISIONAL"),
            std::string::npos);
}

// A calibration directory of our own: a copy of the shipped one, changed by `edit`.
class PerceptCalibration : public ::testing::Test {
 protected:
  std::string copy_calibration() {
    auto dir = test::temp_dir("percept-calibration");
    fs::copy(std::string(SANDPAPER_SOURCE_DIR) + "/calibration", dir + "/calibration", fs::copy_options::recursive);
    return dir + "/calibration";
  }
  compiler::Compiler compiler_on(const std::string& cal) {
    compiler::CompileOptions o;
    o.library_dir = std::string(SANDPAPER_SOURCE_DIR) + "/library";
    o.calibration_dir = cal;
    return compiler::Compiler(o);
  }
};

// The shipped levels of each sourced map compile to the quantity their file places them at.
TEST(PerceptResolution, ShippedLevelsCompileThroughTheirMaps) {
  struct Case { const char* text; const char* parameter; double si; };
  for (const Case& c : {Case{"softness soft", "spring.stiffness", 20 * std::pow(0.630957, -1 / 0.8)},
                        Case{"springiness very-firm", "spring.stiffness", 20 * std::pow(0.15849, -1 / 0.8)},
                        Case{"viscosity very-thick", "damper.damping", 10.0},
                        Case{"slipperiness very-slippery", "friction.coefficient", 0.43},
                        Case{"slipperiness very-sticky", "friction.coefficient", 0.43 / 0.154122}}) {
    SCOPED_TRACE(c.text);
    auto r = compile(c.text);
    ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
    EXPECT_NEAR(provenance(*r.program, c.parameter).value_si, c.si, 1e-9 * c.si);
    // Every level lies inside its map's domain: no extrapolation warning.
    EXPECT_EQ(count(test::codes(r, Severity::Warning), "W0301"), 0u);
  }
  auto typo = compile("softness sof");
  ASSERT_EQ(test::codes(typo), std::vector<std::string>{"E0307"});
  EXPECT_EQ(typo.diagnostics.all()[0].suggestion, "did you mean `soft`?");
}

TEST_F(PerceptCalibration, AWordWithoutAMapIsAnError) {
  auto cal = copy_calibration();
  fs::remove(cal + "/maps/stevens-guirao1964.toml");
  fs::remove(cal + "/levels/viscosity-levels.toml");  // its levels are on that map
  auto r = compiler_on(cal).compile_text("viscosity 0.4");
  ASSERT_EQ(test::codes(r), std::vector<std::string>{"E0320"});
  EXPECT_NE(r.diagnostics.all()[0].suggestion.find("damper 2 N*s/m"), std::string::npos);
}

TEST_F(PerceptCalibration, NamedLevelsComeFromTheLevelsFiles) {
  auto cal = copy_calibration();
  std::ofstream(cal + "/levels/viscosity-levels.toml")
      << "schema = \"sandpaper-levels/1\"\npercept = \"viscosity\"\nmap = \"stevens-guirao1964\"\n"
         "[[level]]\nname = \"syrup\"\nvalue = 0.7\nrationale = \"a test level\"\n";
  auto c = compiler_on(cal);
  auto r = c.compile_text("stickiness syrup");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_NEAR(provenance(*r.program, "damper.damping").value_si, map_file("stevens-guirao1964").value_for(0.7), 1e-12);
  auto typo = c.compile_text("viscosity syrop");
  ASSERT_EQ(test::codes(typo), std::vector<std::string>{"E0307"});
  EXPECT_EQ(typo.diagnostics.all()[0].suggestion, "did you mean `syrup`?");
}

// The warnings follow the map file: a bumpiness map marked measured stops W0320; a viscosity map
// whose apparatus is a joystick stops W0321.
TEST_F(PerceptCalibration, AMeasuredMapDoesNotWarn) {
  auto cal = copy_calibration();
  const auto rewrite = [](const std::string& path, const std::string& from, const std::string& to) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    std::string s = text.str();
    ASSERT_NE(s.find(from), std::string::npos) << path;
    s.replace(s.find(from), from.size(), to);
    std::ofstream(path) << s;
  };
  rewrite(cal + "/maps/bumpiness-provisional.toml", "status = \"provisional\"", "status = \"measured\"");
  rewrite(cal + "/maps/stevens-guirao1964.toml", "apparatus = \"real material\"", "apparatus = \"joystick\"");
  auto c = compiler_on(cal);
  auto b = c.compile_text("bumpiness 0.5; roughness 0.4");
  ASSERT_TRUE(b.ok()) << compiler::format_diagnostics(b.diagnostics);
  EXPECT_EQ(count(test::codes(b, Severity::Warning), "W0320"), 0u);
  auto v = c.compile_text("viscosity 0.4");
  ASSERT_TRUE(v.ok()) << compiler::format_diagnostics(v.diagnostics);
  EXPECT_EQ(count(test::codes(v, Severity::Warning), "W0321"), 0u);
  EXPECT_EQ(count(test::codes(test::shipped_compiler().compile_text("viscosity 0.4"), Severity::Warning), "W0321"), 1u);
}

// [domain] stimuli narrower than the domain (a device map widened to its named levels): inside the
// domain but outside the stimuli compiles with W0322; inside the stimuli, silently. On the shipped
// map b = 10 N*s/m * v^(1/0.42): v = 1 is 10 N*s/m, v = 0.5 is 1.92 N*s/m, very-thin 0.05 N*s/m.
TEST_F(PerceptCalibration, BeyondTheStimuliInsideTheDomainWarnsW0322) {
  auto cal = copy_calibration();
  const std::string map = cal + "/maps/stevens-guirao1964.toml";
  const auto with_stimuli = [&](const std::string& range) {
    std::ifstream in(map);
    std::stringstream text;
    text << in.rdbuf();
    std::string s = text.str();
    const std::string key = "damping = [\"0.05 N*s/m\", \"10 N*s/m\"]\n";
    const auto at = s.find(key);
    if (at == std::string::npos) return false;
    s.insert(at + key.size(), "stimuli = " + range + "\n");
    std::ofstream(map) << s;
    return true;
  };
  ASSERT_TRUE(with_stimuli("[\"0.4 N*s/m\", \"6.4 N*s/m\"]"));
  auto c = compiler_on(cal);
  for (const char* text : {"viscosity 1", "viscosity very-thin"}) {
    auto r = c.compile_text(text);
    ASSERT_TRUE(r.ok()) << text << compiler::format_diagnostics(r.diagnostics);
    EXPECT_EQ(count(test::codes(r, Severity::Warning), "W0322"), 1u) << text;
    EXPECT_EQ(count(test::codes(r, Severity::Warning), "W0301"), 0u) << text;
  }
  auto inside = c.compile_text("viscosity 0.5");
  ASSERT_TRUE(inside.ok());
  EXPECT_EQ(count(test::codes(inside, Severity::Warning), "W0322"), 0u);
  auto above = c.compile_text("viscosity 1.2");
  EXPECT_EQ(test::codes(above), std::vector<std::string>{"E0303"});  // the domain's top still holds

  // Stimuli outside the domain, or in another dimension's unit, are refused by the loader.
  for (const char* bad : {"[\"0.4 N*s/m\", \"20 N*s/m\"]", "[\"0.4 mm\", \"6.4 mm\"]"}) {
    auto other = copy_calibration();
    const std::string other_map = other + "/maps/stevens-guirao1964.toml";
    fs::copy_file(std::string(SANDPAPER_SOURCE_DIR) + "/calibration/maps/stevens-guirao1964.toml", other_map,
                  fs::copy_options::overwrite_existing);
    std::ifstream in(other_map);
    std::stringstream text;
    text << in.rdbuf();
    std::string s = text.str();
    const std::string key = "damping = [\"0.05 N*s/m\", \"10 N*s/m\"]\n";
    s.insert(s.find(key) + key.size(), std::string("stimuli = ") + bad + "\n");
    std::ofstream(other_map) << s;
    EXPECT_THROW(compiler_on(other), calibration::CalibrationError) << bad;
  }
}
