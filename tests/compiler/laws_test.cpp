// The `force` and `physics` statements: each Appendix B law and 3.2.2 model compiles to the term its
// documented law needs, with parameters in SI; errors and warnings for bad or non-passive laws.
#include <cmath>
#include <fstream>
#include <variant>

#include <gtest/gtest.h>

#include "sandpaper/schema/force_laws.hpp"
#include "test_support.hpp"

using namespace sandpaper;

namespace {

schema::PatchProgram compile_ok(const std::string& text) {
  auto r = test::shipped_compiler().compile_text(text);
  EXPECT_TRUE(r.ok()) << text << "\n" << compiler::format_diagnostics(r.diagnostics);
  return r.ok() ? *r.program : schema::PatchProgram{};
}

template <class T>
T only_term(const std::string& text) {
  auto p = compile_ok(text);
  EXPECT_EQ(p.terms.size(), 1u) << text;
  if (p.terms.size() != 1 || !std::holds_alternative<T>(p.terms[0])) {
    ADD_FAILURE() << text << ": not the expected term kind";
    return T{};
  }
  return std::get<T>(p.terms[0]);
}

}  // namespace

TEST(Laws, SpringBumpAndTheLinearFields) {
  EXPECT_DOUBLE_EQ(only_term<schema::SpringTerm>("force Spring stiffness 200 N/m").stiffness_N_per_m, 200);
  EXPECT_DOUBLE_EQ(only_term<schema::SpringTerm>("physics RadialSpring stiffness 0.3 N/mm").stiffness_N_per_m, 300);
  // Bump F = k p: radial gain +k. Circle: a quarter-turn field. Buckle: both.
  auto bump = only_term<schema::LinearFieldTerm>("force Bump stiffness 150 N/m");
  EXPECT_DOUBLE_EQ(bump.radial_N_per_m, 150);
  EXPECT_DOUBLE_EQ(bump.tangential_N_per_m, 0);
  auto circle = only_term<schema::LinearFieldTerm>("force Circle stiffness 40 N/m");
  EXPECT_DOUBLE_EQ(circle.radial_N_per_m, 0);
  EXPECT_DOUBLE_EQ(circle.tangential_N_per_m, 40);
  auto buckle = only_term<schema::LinearFieldTerm>("force Buckle radial -20 N/m tangential 30 N/m");
  EXPECT_DOUBLE_EQ(buckle.radial_N_per_m, -20);
  EXPECT_DOUBLE_EQ(buckle.tangential_N_per_m, 30);
  auto line = only_term<schema::LinearSpringTerm>("physics LinearSpring stiffness 100 N/m orientation 90 deg");
  EXPECT_DOUBLE_EQ(line.stiffness_N_per_m, 100);
  EXPECT_NEAR(line.orientation_rad, M_PI / 2, 1e-15);
}

TEST(Laws, ViscousIsADamperAndAntiViscousItsNegative) {
  EXPECT_DOUBLE_EQ(only_term<schema::DamperTerm>("force Viscous damping 3 N*s/m").damping_Ns_per_m, 3);
  EXPECT_DOUBLE_EQ(only_term<schema::DamperTerm>("force AntiViscous damping 3 N*s/m").damping_Ns_per_m, -3);
  EXPECT_DOUBLE_EQ(only_term<schema::NapTerm>("force Nap damping 1.5 N*s/m").damping_Ns_per_m, 1.5);
}

TEST(Laws, PeriodicLawsKeepShapeAmplitudePeriodAndAxes) {
  auto wave = only_term<schema::PeriodicTerm>("force Wave amplitude 50 gf period 4 mm");
  EXPECT_EQ(wave.shape, schema::PeriodicShape::Sine);
  EXPECT_DOUBLE_EQ(wave.amplitude_N, 50 * 9.80665e-3);
  EXPECT_DOUBLE_EQ(wave.period_m, 0.004);
  EXPECT_TRUE(wave.on_x && wave.on_y);  // default: a grid, as the thesis' triangle wave on both axes
  auto cusp = only_term<schema::PeriodicTerm>("force Cusp amplitude 1 N period 2 mm axes y");
  EXPECT_EQ(cusp.shape, schema::PeriodicShape::Sawtooth);
  EXPECT_FALSE(cusp.on_x);
  EXPECT_TRUE(cusp.on_y);
  auto tri = only_term<schema::PeriodicTerm>("force Triangle amplitude 30 pu period 3 mm axes x");
  EXPECT_EQ(tri.shape, schema::PeriodicShape::Triangle);
  EXPECT_NEAR(tri.amplitude_N, 30 * 4 * 0.490909 * 9.80665e-3, 1e-12);  // program units, Table 6
  EXPECT_TRUE(tri.on_x);
  EXPECT_FALSE(tri.on_y);
}

TEST(Laws, TheRemainingTextureMenuLaws) {
  auto c = only_term<schema::ConstantForceTerm>("force Const x 0.2 N y -150 mN");
  EXPECT_DOUBLE_EQ(c.force_N[0], 0.2);
  EXPECT_DOUBLE_EQ(c.force_N[1], -0.15);
  auto ridge = only_term<schema::RidgeTerm>("force Ridge stiffness 80 N/m wavelength 10 mm width 3 mm");
  EXPECT_DOUBLE_EQ(ridge.wavelength_m, 0.01);
  EXPECT_DOUBLE_EQ(ridge.ridge_width_m, 0.003);
  auto bowl = only_term<schema::BowlTerm>("force Bowl stiffness 100 N/m");
  EXPECT_DOUBLE_EQ(bowl.radius_m, 0.02);  // the documented default reference radius
  auto minus = only_term<schema::MinusTerm>("force Minus stiffness 50 N/m lead 10 ms");
  EXPECT_DOUBLE_EQ(minus.lead_s, 0.01);
  auto follower = only_term<schema::FollowerSpringTerm>("force ATNSpring stiffness 200 N/m");
  EXPECT_DOUBLE_EQ(follower.lag_s, 0.1);
  EXPECT_TRUE(compile_ok("force Nothing").terms.empty());
  EXPECT_TRUE(compile_ok("force Null").terms.empty());
}

TEST(Laws, PhysicsModels) {
  auto one = only_term<schema::PointMassesTerm>("physics Mass mass 50 g stiffness 100 N/m damping 0.2 N*s/m");
  EXPECT_EQ(one.count, 1u);
  EXPECT_DOUBLE_EQ(one.mass_kg[0], 0.05);
  EXPECT_DOUBLE_EQ(one.damping_Ns_per_m[0], 0.2);
  EXPECT_EQ(one.gravity_m_s2[1], 0);
  auto two = only_term<schema::PointMassesTerm>(
      "physics TwoMasses mass 50 g stiffness 100 N/m mass2 30 g stiffness2 60 N/m friction 0.1 N*s/m");
  EXPECT_EQ(two.count, 2u);
  EXPECT_DOUBLE_EQ(two.mass_kg[1], 0.03);
  EXPECT_DOUBLE_EQ(two.stiffness_N_per_m[1], 60);
  EXPECT_DOUBLE_EQ(two.ground_damping_Ns_per_m, 0.1);
  auto brick = only_term<schema::PointMassesTerm>("physics Brick mass 200 g stiffness 50 N/m");
  EXPECT_DOUBLE_EQ(brick.gravity_m_s2[0], 0);
  EXPECT_DOUBLE_EQ(brick.gravity_m_s2[1], -9.80665);
  auto attractor = only_term<schema::AttractorTerm>("physics Attractor stiffness 30 N/m radius 25 mm period 3 s swirl 0");
  EXPECT_DOUBLE_EQ(attractor.radius_m, 0.025);
  EXPECT_DOUBLE_EQ(attractor.period_s, 3);
  EXPECT_DOUBLE_EQ(attractor.swirl, 0);
}

TEST(Laws, EveryLawInTheTableCompiles) {
  for (const auto& def : schema::all_laws()) {
    std::string text(schema::family_keyword(def.family));
    text += " " + std::string(def.name);
    for (const auto& p : def.params) {
      if (!p.required) continue;
      text += " " + std::string(p.name) + " ";
      switch (p.dimension) {
        case schema::Dimension::Stiffness: text += "100 N/m"; break;
        case schema::Dimension::Damping: text += "1 N*s/m"; break;
        case schema::Dimension::Force: text += "0.5 N"; break;
        case schema::Dimension::Length: text += "4 mm"; break;
        case schema::Dimension::Mass: text += "100 g"; break;
        case schema::Dimension::Fraction: text += "0.5"; break;  // a plain number (Friction's coefficients)
        default: ADD_FAILURE() << "no example for " << def.name << " " << p.name;
      }
    }
    auto r = test::shipped_compiler().compile_text(text);
    EXPECT_TRUE(r.ok()) << text << "\n" << compiler::format_diagnostics(r.diagnostics);
  }
}

TEST(Laws, TermsAreSummedInTheOrderWritten) {
  auto p = compile_ok("grating period 2 mm amplitude 1 N; force Viscous damping 2 N*s/m; force Const x 0.1 N; spring 50 N/m");
  ASSERT_EQ(p.terms.size(), 4u);
  EXPECT_TRUE(std::holds_alternative<schema::GratingTerm>(p.terms[0]));
  EXPECT_TRUE(std::holds_alternative<schema::SpringTerm>(p.terms[1]));  // the shorthand `spring` comes with the texture
  EXPECT_TRUE(std::holds_alternative<schema::DamperTerm>(p.terms[2]));
  EXPECT_TRUE(std::holds_alternative<schema::ConstantForceTerm>(p.terms[3]));
}

TEST(Laws, NonPassiveLawsWarnAndGetAnEnergyBound) {
  for (const char* text : {"force AntiViscous damping 2 N*s/m", "force Nap damping 1 N*s/m", "force Minus stiffness 50 N/m",
                           "force Circle stiffness 20 N/m", "force Buckle tangential 5 N/m", "force ATNSpring stiffness 50 N/m",
                           "physics Attractor stiffness 20 N/m"}) {
    auto r = test::shipped_compiler().compile_text(text);
    ASSERT_TRUE(r.ok()) << text;
    EXPECT_EQ(test::codes(r, compiler::Severity::Warning), std::vector<std::string>{"W0306"}) << text;
    EXPECT_DOUBLE_EQ(r.program->energy_budget_J, 0.05) << text;
    EXPECT_DOUBLE_EQ(r.program->energy_refill_W, 0.01) << text;
  }
  for (const char* text : {"force Viscous damping 2 N*s/m", "force Bump stiffness 20 N/m", "force Buckle radial 5 N/m",
                           "physics Mass mass 50 g stiffness 100 N/m", "force Wave amplitude 1 N period 3 mm"}) {
    auto r = test::shipped_compiler().compile_text(text);
    ASSERT_TRUE(r.ok()) << text;
    EXPECT_TRUE(test::codes(r, compiler::Severity::Warning).empty()) << text;
    EXPECT_EQ(r.program->energy_budget_J, 0) << text;
  }
  auto stated = compile_ok("force AntiViscous damping 2 N*s/m; energy budget 20 mJ refill 5 mW");
  EXPECT_DOUBLE_EQ(stated.energy_budget_J, 0.02);
  EXPECT_DOUBLE_EQ(stated.energy_refill_W, 0.005);
  EXPECT_EQ(test::provenance(stated, "energy.budget").layer, "physical");
}

TEST(Laws, BadLawsAreErrorsThatSayWhatToWrite) {
  auto codes_of = [](const std::string& text) { return test::codes(test::shipped_compiler().compile_text(text)); };
  EXPECT_EQ(codes_of("force Circl stiffness 3 N/m"), std::vector<std::string>{"E0211"});
  EXPECT_EQ(codes_of("physics Spring stiffness 3 N/m"), std::vector<std::string>{"E0211"});  // Spring is a force law
  EXPECT_EQ(codes_of("force Wave amplitude 1 N"), std::vector<std::string>{"E0311"});
  EXPECT_EQ(codes_of("force Spring stiffness 3 N"), std::vector<std::string>{"E0205"});
  EXPECT_EQ(codes_of("force Spring stiffnes 3 N/m"), std::vector<std::string>{"E0209"});
  EXPECT_EQ(codes_of("force Spring stiffness 3 N/m stiffness 4 N/m"), std::vector<std::string>{"E0206"});
  EXPECT_EQ(codes_of("force Spring stiffness -3 N/m"), std::vector<std::string>{"E0304"});
  EXPECT_EQ(codes_of("force Wave amplitude 1 N period 2 mm axes z"), std::vector<std::string>{"E0217"});
  EXPECT_EQ(codes_of("force Nothing stiffness 3 N/m"), std::vector<std::string>{"E0209"});
  EXPECT_EQ(codes_of("damper -2 N*s/m"), std::vector<std::string>{"E0304"});
  // A light mass on a stiff spring cannot be integrated at 900 Hz within the substep cap.
  EXPECT_EQ(codes_of("physics Mass mass 0.01 g stiffness 20000 N/m"), std::vector<std::string>{"E0312"});
  auto r = test::shipped_compiler().compile_text("force Wave amplitude 1 N");
  ASSERT_FALSE(r.diagnostics.all().empty());
  EXPECT_NE(r.diagnostics.all()[0].suggestion.find("period"), std::string::npos);
}

TEST(Laws, AFilesLawsReplaceTheInheritedOnes) {
  const std::string dir = test::temp_dir("laws-inherit");
  {
    std::ofstream(dir + "/sticky.hmat") << "force Viscous damping 4 N*s/m\nforce Const x 0.1 N\n";
  }
  compiler::Compiler c({.device = "sim", .library_dir = dir, .calibration_dir = {}, .library_path = {}});
  auto inherited = c.compile_text("like sticky");
  ASSERT_TRUE(inherited.ok()) << compiler::format_diagnostics(inherited.diagnostics);
  EXPECT_EQ(inherited.program->terms.size(), 2u);
  EXPECT_EQ(test::provenance(*inherited.program, "force.Viscous.damping").layer, "representative");
  auto replaced = c.compile_text("like sticky; force Spring stiffness 10 N/m");
  ASSERT_TRUE(replaced.ok());
  ASSERT_EQ(replaced.program->terms.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<schema::SpringTerm>(replaced.program->terms[0]));
}

TEST(Laws, SubstepsFollowTheStiffestLink) {
  schema::PointMassesTerm t;
  t.mass_kg[0] = 0.1;
  t.stiffness_N_per_m[0] = 1000;  // omega = 100 rad/s
  EXPECT_EQ(schema::point_mass_substeps(t, 1e-3), 1u);   // h omega = 0.1
  EXPECT_EQ(schema::point_mass_substeps(t, 1e-2), 4u);   // 1.0 / 0.25
  t.damping_Ns_per_m[0] = 10;                             // c / m = 100 1/s
  EXPECT_EQ(schema::point_mass_substeps(t, 1e-2), 4u);   // 1.0 / 0.5 = 2 < 4
  t.damping_Ns_per_m[0] = 50;                             // c / m = 500 1/s
  EXPECT_EQ(schema::point_mass_substeps(t, 1e-2), 10u);  // 5 / 0.5
}
