// Every Appendix B force law and every 3.2.2 physics model, compiled from its statement and played on
// the simulated joystick (virtual clock, 1 kHz, a circling hand): each tick's recorded force is
// checked against the thesis' formula evaluated directly on that tick's recorded position, on the
// velocity and acceleration the loop documents (first-order low-pass, 50 Hz, of finite differences),
// and, for models with state, on state integrated here independently. Forces in newtons.
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "test_support.hpp"

using namespace sandpaper;
using glm::dvec2;

namespace {

constexpr double kRate = 1000;
constexpr double kDt = 1 / kRate;

// What the loop knew at one tick: position as recorded, velocity and acceleration restated from
// runtime/include/sandpaper/runtime/servo_loop.hpp's documented filter.
struct Tick {
  double t;
  dvec2 p, v, a, force;
};

std::vector<Tick> play(const std::string& text, runtime::HandScript script, double seconds = 2.0) {
  auto r = test::shipped_compiler().compile_text(text);
  EXPECT_TRUE(r.ok()) << text << "\n" << compiler::format_diagnostics(r.diagnostics);
  if (!r.ok()) return {};
  runtime::ServoConfig cfg;
  cfg.rate_hz = kRate;
  cfg.duration_s = seconds;
  // No start ramp: these checks compare each tick's force with the law's (SafetyRamp tests the ramp).
  cfg.ramp_s = 0;
  const auto ticks = static_cast<std::size_t>(std::llround(seconds * kRate));
  runtime::SimJoystick sim(runtime::sim_device_limits(), script, ticks);
  runtime::PatchEvaluator ev(*r.program);
  runtime::VirtualClock clock;
  auto report = runtime::run_servo_loop(sim, ev, clock, cfg);
  EXPECT_EQ(report.stop_reason, "completed") << text;
  EXPECT_EQ(report.clamped_ticks, 0u) << text;

  std::vector<Tick> out;
  const double rc = 1 / (2 * std::numbers::pi * 50.0);
  dvec2 v{0, 0}, a{0, 0};
  for (std::size_t k = 0; k < sim.records().size(); ++k) {
    const auto& rec = sim.records()[k];
    if (k > 0) {
      const auto& prev = sim.records()[k - 1];
      const double dt = rec.t_s - prev.t_s;
      const double g = dt / (dt + rc);
      const dvec2 v_prev = v;
      v += g * ((rec.position_m - prev.position_m) / dt - v);
      a += g * ((v - v_prev) / dt - a);
    }
    out.push_back({rec.t_s, rec.position_m, v, a, rec.force_N});
  }
  return out;
}

runtime::HandScript circle(double radius = 0.03, double speed = 0.06) {
  runtime::HandScript s;
  s.path = runtime::HandPath::Circle;
  s.amplitude_m = radius;
  s.speed_m_s = speed;
  return s;
}

double frac(double x) { return x - std::floor(x); }
dvec2 r90(dvec2 p) { return {-p.y, p.x}; }

// Compares every tick; `tolerance_N` absolute.
void expect_law(const std::string& text, const std::function<dvec2(const Tick&)>& law, double tolerance_N = 1e-9,
                runtime::HandScript script = circle()) {
  auto ticks = play(text, script);
  ASSERT_FALSE(ticks.empty()) << text;
  double worst = 0, biggest = 0;
  std::size_t worst_at = 0;
  for (std::size_t k = 0; k < ticks.size(); ++k) {
    const dvec2 want = law(ticks[k]);
    const double err = glm::length(ticks[k].force - want);
    biggest = std::max(biggest, glm::length(want));
    if (err > worst) {
      worst = err;
      worst_at = k;
    }
  }
  EXPECT_LE(worst, tolerance_N) << text << ": worst tick " << worst_at << " force (" << ticks[worst_at].force.x << ", "
                                << ticks[worst_at].force.y << ") N, formula (" << law(ticks[worst_at]).x << ", "
                                << law(ticks[worst_at]).y << ") N";
  EXPECT_GT(biggest, 0.05) << text << ": the path never made the law push";
}

// Single-precision-free laws are computed in double by both sides; 1e-9 N is rounding.
TEST(ForceLawsPlayed, PositionLaws) {
  expect_law("force Spring stiffness 20 N/m", [](const Tick& t) { return -20.0 * t.p; });
  expect_law("physics RadialSpring stiffness 20 N/m", [](const Tick& t) { return -20.0 * t.p; });
  expect_law("force Bump stiffness 20 N/m", [](const Tick& t) { return 20.0 * t.p; });
  expect_law("force Bowl stiffness 30 N/m radius 20 mm",
             [](const Tick& t) { return -30.0 * t.p * std::sqrt(glm::length(t.p) / 0.02); });
  expect_law("force Circle stiffness 25 N/m; energy budget 100 J", [](const Tick& t) { return 25.0 * r90(t.p); });
  expect_law("force Buckle radial -10 N/m tangential 15 N/m; energy budget 100 J",
             [](const Tick& t) { return -10.0 * t.p + 15.0 * r90(t.p); });
  expect_law("force Const x 0.3 N y -0.2 N", [](const Tick&) { return dvec2{0.3, -0.2}; });
  expect_law("physics LinearSpring stiffness 40 N/m orientation 30 deg", [](const Tick& t) {
    const dvec2 n{std::cos(std::numbers::pi / 6), std::sin(std::numbers::pi / 6)};
    return -40.0 * glm::dot(t.p, n) * n;
  });
  expect_law("force Ridge stiffness 50 N/m wavelength 10 mm width 3 mm", [](const Tick& t) {
    const double m = t.p.x - 0.01 * std::floor(t.p.x / 0.01);  // p_x mod wavelength, in [0, wavelength)
    return dvec2{50.0 * (m - 0.003), 0};
  });
}

TEST(ForceLawsPlayed, PeriodicLaws) {
  const double A = 0.4, P = 0.004;
  expect_law("force Wave amplitude 0.4 N period 4 mm", [&](const Tick& t) {
    return dvec2{-A * std::sin(2 * std::numbers::pi * t.p.x / P), -A * std::sin(2 * std::numbers::pi * t.p.y / P)};
  });
  expect_law("force Cusp amplitude 0.4 N period 4 mm axes x", [&](const Tick& t) {
    return dvec2{A * (2 * frac(std::abs(t.p.x) / P) - 1), 0};
  });
  expect_law("force Triangle amplitude 0.4 N period 4 mm axes y", [&](const Tick& t) {
    return dvec2{0, -A * (2 * frac(t.p.y / P) - 1)};
  });
}

TEST(ForceLawsPlayed, VelocityLaws) {
  // Energy budgets far above what these 2 s inject, so the bound does not scale the laws here.
  expect_law("force Viscous damping 3 N*s/m", [](const Tick& t) { return -3.0 * t.v; });
  expect_law("force AntiViscous damping 3 N*s/m; energy budget 100 J", [](const Tick& t) { return 3.0 * t.v; });
  expect_law("force Nap damping 3 N*s/m; energy budget 100 J",
             [](const Tick& t) { return dvec2{-3.0 * t.v.x, std::abs(3.0 * t.v.y)}; });
  expect_law("force Minus stiffness 40 N/m lead 20 ms; energy budget 100 J",
             [](const Tick& t) { return -40.0 * (t.v * 0.02 + 0.5 * t.a * 0.02 * 0.02); });
}

// The perceptual words play the law their map gives: the damping or stiffness is read here from the
// map file itself and the force checked tick by tick. (slipperiness compiles to Coulomb friction,
// whose stick band makes it stateful: tests/compiler/percepts_test.cpp checks its term, and
// tests/runtime/friction_test.cpp the law.)
TEST(ForceLawsPlayed, PerceptualWordsPlayThroughTheirMaps) {
  const auto map = [](const char* id) {
    return calibration::load_map_file(std::string(SANDPAPER_SOURCE_DIR) + "/calibration/maps/" + id + ".toml");
  };
  const double b = map("stevens-guirao1964").value_for(0.5);  // 1.92 N*s/m
  expect_law("viscosity 0.5", [&](const Tick& t) { return -b * t.v; });
  expect_law("stickiness 0.5", [&](const Tick& t) { return -b * t.v; });
  const double k = map("harper-stevens1964").value_for(0.5);  // 47.6 N/m
  expect_law("softness 0.5", [&](const Tick& t) { return -k * t.p; });
  expect_law("springiness 0.5", [&](const Tick& t) { return -k * t.p; });
}

TEST(ForceLawsPlayed, FollowerSpringLagsTheHand) {
  // m follows p with an exact first-order lag, starting under the hand; advanced, then felt.
  dvec2 m{0, 0};
  bool first = true;
  double last_t = 0;
  // Active (it pushes along the recent motion): a budget far above what 2 s inject keeps the bound out.
  expect_law("force ATNSpring stiffness 60 N/m lag 50 ms; energy budget 100 J", [&](const Tick& t) {
    if (first) {
      m = t.p;
      first = false;
    } else {
      m += (1 - std::exp(-(t.t - last_t) / 0.05)) * (t.p - m);
    }
    last_t = t.t;
    return 60.0 * (t.p - m);
  });
}

TEST(ForceLawsPlayed, AttractorFollowsItsSwirl) {
  const double r = 0.02, T = 1.5, s = 0.3;
  double t0 = -1;
  expect_law("physics Attractor stiffness 30 N/m radius 20 mm period 1.5 s swirl 0.3; energy budget 100 J",
             [&](const Tick& t) {
               if (t0 < 0) t0 = t.t;
               const double theta = 2 * std::numbers::pi * (t.t - t0) / T;
               const dvec2 q = r * (1 + s * std::sin(3 * theta)) / (1 + s) * dvec2{std::cos(theta), std::sin(theta)};
               return -30.0 * (t.p - q);
             },
             1e-6);
}

// One mass on a spring, with ground friction only (so the hand's velocity does not enter), against
// an RK4 integration of m x'' = k (p - x) - c x' with the hand held at each tick's position.
TEST(ForceLawsPlayed, MassOnASpringMatchesAnIndependentIntegration) {
  const double m = 0.05, k = 100, c = 0.1;
  dvec2 x{0, 0}, xv{0, 0};
  bool first = true;
  double last_t = 0;
  auto deriv = [&](dvec2 pos, dvec2 vel, dvec2 hand) { return (k * (hand - pos) - c * vel) / m; };
  expect_law("physics Mass mass 50 g stiffness 100 N/m friction 0.1 N*s/m",
             [&](const Tick& t) {
               if (first) {
                 x = t.p;
                 first = false;
               } else {
                 const int n = 20;
                 const double h = (t.t - last_t) / n;
                 for (int i = 0; i < n; ++i) {
                   const dvec2 a1 = deriv(x, xv, t.p), v1 = xv;
                   const dvec2 a2 = deriv(x + 0.5 * h * v1, xv + 0.5 * h * a1, t.p), v2 = xv + 0.5 * h * a1;
                   const dvec2 a3 = deriv(x + 0.5 * h * v2, xv + 0.5 * h * a2, t.p), v3 = xv + 0.5 * h * a2;
                   const dvec2 a4 = deriv(x + h * v3, xv + h * a3, t.p), v4 = xv + h * a3;
                   x += h / 6 * (v1 + 2.0 * v2 + 2.0 * v3 + v4);
                   xv += h / 6 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
                 }
               }
               last_t = t.t;
               return -k * (t.p - x);
             },
             0.03 * 100 * 0.03);  // 3 % of the largest spring force the 30 mm circle can make
}

TEST(ForceLawsPlayed, BrickHangsBelowTheHand) {
  // Held still, the brick settles where the spring carries its weight: F_hand = -m g (downward).
  runtime::HandScript still = circle(0.0, 0.0);
  auto ticks = play("physics Brick mass 200 g stiffness 50 N/m damping 2 N*s/m", still, 3.0);
  ASSERT_FALSE(ticks.empty());
  const dvec2 settled = ticks.back().force;
  EXPECT_NEAR(settled.x, 0, 1e-6);
  EXPECT_NEAR(settled.y, -0.2 * 9.80665, 0.01);
}

TEST(ForceLawsPlayed, TheEnergyBoundStopsAntiViscousFromInjectingMore) {
  // A budget of 20 mJ and a 5 mW refill: over 2 s, AntiViscous may give at most 30 mJ.
  auto ticks = play("force AntiViscous damping 4 N*s/m; energy budget 20 mJ refill 5 mW", circle(0.03, 0.1));
  ASSERT_FALSE(ticks.empty());
  double injected = 0;
  for (std::size_t k = 1; k < ticks.size(); ++k)
    injected += glm::dot(ticks[k].force, ticks[k].v) * (ticks[k].t - ticks[k - 1].t);
  const double unbounded = 4 * 0.1 * 0.1 * 2.0;  // b v^2 t = 80 mJ without the bound
  EXPECT_LE(injected, 0.020 + 0.005 * 2.0 + 1e-4);
  EXPECT_GT(injected, 0.020);  // and it did inject what the budget allows: the law is not silenced
  EXPECT_LT(injected, unbounded);
}

}  // namespace

// Friction played on the scripted scan (docs/FORCE_LAWS.md, "Friction"): while the hand slides the force
// is mu_k P against the motion; each turn re-sticks the contact, and the next stroke starts only when
// the presliding spring reaches mu_s P; the force never passes mu_s P by more than one tick's travel.
TEST(ForceLawsPlayed, FrictionSlidesAtKineticAndBreaksLooseAtStatic) {
  auto r = test::shipped_compiler().compile_text("physics Friction static 0.8 kinetic 0.5 press 2 N");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_TRUE(test::codes(r, compiler::Severity::Warning).empty());  // passive: no W0306, no energy bound
  EXPECT_EQ(r.program->energy_budget_J, 0.0);
  runtime::HandScript scan;
  scan.speed_m_s = 0.05;
  scan.amplitude_m = 0.02;
  runtime::ServoConfig cfg;
  cfg.duration_s = 3.0;
  cfg.ramp_s = 0;
  runtime::SimJoystick sim(runtime::sim_device_limits(), scan, 3000);
  runtime::PatchEvaluator ev(*r.program);
  runtime::VirtualClock clock;
  ASSERT_EQ(runtime::run_servo_loop(sim, ev, clock, cfg).stop_reason, "completed");
  const auto& rec = sim.records();
  const double step = 0.05 / 1000, k = 2000;
  int sliding = 0;
  double peak = 0;
  for (std::size_t i = 1; i + 1 < rec.size(); ++i) {
    const double v = rec[i + 1].position_m.x - rec[i - 1].position_m.x;
    const double f = rec[i].force_N.x;
    peak = std::max(peak, std::abs(f));
    if (std::abs(std::abs(f) - 0.5 * 2) < 1e-9 && std::abs(v) > 0.5 * step) {
      ++sliding;
      EXPECT_LT(f * v, 0) << i;  // against the motion
    }
  }
  EXPECT_GT(sliding, 2000);  // most of the run slides at mu_k P
  EXPECT_GT(peak, 0.8 * 2 - k * step);
  EXPECT_LE(peak, 0.8 * 2 + k * step);
  // Kinetic above static is refused when compiling.
  EXPECT_EQ(test::codes(test::shipped_compiler().compile_text("physics Friction static 0.5 kinetic 0.8 press 1 N")),
            std::vector<std::string>{"E0304"});
}

// Velvet from the library, stroked up and down the nap on the scripted scan (docs/FORCE_LAWS.md, "Nap
// friction"): toward +y, with the nap, the contact slides at 0.2 N; toward -y, against it, at 0.5 N.
TEST(ForceLawsPlayed, VelvetDragsAgainstTheNapAndGlidesWithIt) {
  runtime::HandScript scan;
  scan.speed_m_s = 0.05;
  scan.amplitude_m = 0.02;
  scan.direction_rad = std::numbers::pi / 2;  // along y, with the nap's lie and back
  const auto rec = play("like velvet", scan, 3.0);
  ASSERT_FALSE(rec.empty());
  const double step = 0.05 / 1000;
  int with = 0, against = 0, other = 0;
  for (std::size_t i = 1; i + 1 < rec.size(); ++i) {
    const double v = rec[i + 1].p.y - rec[i - 1].p.y;
    const double f = rec[i].force.y;
    if (std::abs(v) < 0.5 * step) continue;
    if (v > 0 && std::abs(f + 0.2) < 1e-9) ++with;
    else if (v < 0 && std::abs(f - 0.5) < 1e-9) ++against;
    else ++other;
  }
  // Most of each stroke slides; the rest is the presliding spring after each turn.
  EXPECT_GT(with, 1000);
  EXPECT_GT(against, 1000);
  EXPECT_LT(other, with / 4);
  // Each pair's kinetic above its static is refused, each with its own diagnostic.
  const std::string pairs = "physics NapFriction press 1 N static 0.3 kinetic 0.2 ";
  EXPECT_EQ(test::codes(test::shipped_compiler().compile_text(pairs + "against_static 0.5 against_kinetic 0.8")),
            std::vector<std::string>{"E0304"});
  EXPECT_EQ(test::codes(test::shipped_compiler().compile_text(
                "physics NapFriction press 1 N static 0.2 kinetic 0.3 against_static 0.5 against_kinetic 0.8")),
            (std::vector<std::string>{"E0304", "E0304"}));
  EXPECT_TRUE(test::codes(test::shipped_compiler().compile_text(pairs + "against_static 0.8 against_kinetic 0.5")).empty());
}
