// The physics patch of point masses (thesis 3.2.2): the force on the hand against an independent
// RK4 solution of the chain's equations, energy kept over 10 s with an undamped link, stability of a
// stiff light mass at the joystick's 900 Hz, the substep rule, and the rest state under gravity.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "term_samples.hpp"

namespace sandpaper::runtime {
namespace {

using namespace testing;

// The chain's state for the reference solution: x0, v0, x1, v1.
using Chain = std::array<glm::dvec2, 4>;

// Newton's law for each mass, written from the description: link 0 (spring k0, damper c0) joins the
// hand to mass 0, link 1 joins mass 0 to mass 1, each mass has ground damping cg and weight m g.
Chain derivative(const schema::PointMassesTerm& t, const Chain& s, glm::dvec2 p, glm::dvec2 v) {
  const glm::dvec2 g{t.gravity_m_s2[0], t.gravity_m_s2[1]};
  const glm::dvec2 link0 = t.stiffness_N_per_m[0] * (p - s[0]) + t.damping_Ns_per_m[0] * (v - s[1]);
  glm::dvec2 link1{0, 0};
  if (t.count == 2) link1 = t.stiffness_N_per_m[1] * (s[0] - s[2]) + t.damping_Ns_per_m[1] * (s[1] - s[3]);
  const glm::dvec2 a0 = (link0 - link1 - t.ground_damping_Ns_per_m * s[1]) / t.mass_kg[0] + g;
  glm::dvec2 a1{0, 0};
  if (t.count == 2) a1 = (link1 - t.ground_damping_Ns_per_m * s[3]) / t.mass_kg[1] + g;
  return {s[1], a0, s[3], a1};
}

Chain add(const Chain& s, const Chain& d, double h) {
  Chain out;
  for (int i = 0; i < 4; ++i) out[i] = s[i] + h * d[i];
  return out;
}

void rk4(const schema::PointMassesTerm& t, Chain& s, glm::dvec2 p, glm::dvec2 v, double h) {
  const Chain k1 = derivative(t, s, p, v);
  const Chain k2 = derivative(t, add(s, k1, h / 2), p, v);
  const Chain k3 = derivative(t, add(s, k2, h / 2), p, v);
  const Chain k4 = derivative(t, add(s, k3, h), p, v);
  for (int i = 0; i < 4; ++i) s[i] += h / 6 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

// Largest difference between the evaluator's force and the RK4 reference's over `duration` s at
// `rate_hz`, as a fraction of the largest reference force. The hand runs a circle; each tick's sample
// is held over the interval before it, as the evaluator does. The reference starts where reset puts
// the masses, computed here from the static balance: x0 = p + (m0 + m1) g / k0, x1 = x0 + m1 g / k1.
double relative_error_against_rk4(const schema::PointMassesTerm& term, double rate_hz, double duration_s) {
  const auto program = program_of({term});
  PatchEvaluator evaluator(program);
  const SimJoystick path(sim_device_limits(), HandScript{HandPath::Circle, 0.12, 0.03, 0.0}, 0);
  const glm::dvec2 g{term.gravity_m_s2[0], term.gravity_m_s2[1]};
  const double dt = 1.0 / rate_hz;

  HandState hand;
  hand.position_m = path.hand_position(0);
  evaluator.reset_rt(hand);
  Chain s{};
  s[0] = hand.position_m + (term.mass_kg[0] + (term.count == 2 ? term.mass_kg[1] : 0)) / term.stiffness_N_per_m[0] * g;
  s[2] = s[0] + (term.count == 2 ? term.mass_kg[1] / term.stiffness_N_per_m[1] : 0.0) * g;

  double worst = 0, largest = 0;
  const int ticks = static_cast<int>(duration_s * rate_hz);
  for (int k = 0; k <= ticks; ++k) {
    const double t = k * dt;
    hand.position_m = path.hand_position(t);
    hand.velocity_m_s = (path.hand_position(t + 1e-5) - path.hand_position(t - 1e-5)) / 2e-5;
    if (k > 0)
      for (int i = 0; i < 200; ++i) rk4(term, s, hand.position_m, hand.velocity_m_s, dt / 200);
    const glm::dvec2 got = evaluator.force_rt(hand, k == 0 ? 0.0 : dt);
    const glm::dvec2 want = -term.stiffness_N_per_m[0] * (hand.position_m - s[0]) -
                            term.damping_Ns_per_m[0] * (hand.velocity_m_s - s[1]);
    worst = std::max(worst, glm::length(got - want));
    largest = std::max(largest, glm::length(want));
  }
  EXPECT_GT(largest, 0.2) << "the circle should swing the masses";
  return worst / largest;
}

TEST(PointMasses, OneMassMatchesRk4AndConvergesWithTheServoRate) {
  const auto term = one_mass(0.2, 200, 0.8, 0.2);
  const double at_1k = relative_error_against_rk4(term, 1000, 3.0);
  const double at_10k = relative_error_against_rk4(term, 10000, 3.0);
  EXPECT_LT(at_1k, 0.03);
  // Semi-implicit Euler is first order: ten times the rate, about a tenth of the error.
  EXPECT_LT(at_10k, 0.2 * at_1k);
}

TEST(PointMasses, TwoMassesMatchRk4) {
  const auto term = two_masses(0.15, 0.1, 250, 120, 0.6, 0.3, 0.1, 0.5, -9.81);
  const double at_1k = relative_error_against_rk4(term, 1000, 3.0);
  const double at_10k = relative_error_against_rk4(term, 10000, 3.0);
  EXPECT_LT(at_1k, 0.03);
  EXPECT_LT(at_10k, 0.2 * at_1k);
}

struct EnergyTrace {
  double min_J = 1e300, max_J = -1e300;
  double first_second_mean_J = 0, last_second_mean_J = 0;
  double initial_J = 0;
};

// One mass on an undamped link hanging from a hand that steps by `step` at t = 0 and is then held
// still for `duration` s. Energy of the swing about the new rest point: (1/2) m v^2 + (1/2) k |x - x_rest|^2,
// x_rest = p + m g / k (gravity's potential folded in).
EnergyTrace swing_energy(const schema::PointMassesTerm& term, double rate_hz, double duration_s, glm::dvec2 step) {
  const auto program = program_of({term});
  PatchEvaluator evaluator(program);
  HandState hand;
  evaluator.reset_rt(hand);
  hand.position_m = step;
  const glm::dvec2 rest = step + term.mass_kg[0] / term.stiffness_N_per_m[0] * glm::dvec2{term.gravity_m_s2[0], term.gravity_m_s2[1]};
  const auto energy = [&] {
    const TermState& s = *evaluator.state_of(0);
    const glm::dvec2 dx = s.masses.position_m[0] - rest, v = s.masses.velocity_m_s[0];
    return 0.5 * term.mass_kg[0] * glm::dot(v, v) + 0.5 * term.stiffness_N_per_m[0] * glm::dot(dx, dx);
  };
  EnergyTrace trace;
  trace.initial_J = energy();
  const int ticks = static_cast<int>(std::lround(duration_s * rate_hz));
  const int second = static_cast<int>(std::lround(rate_hz));
  for (int k = 1; k <= ticks; ++k) {
    const glm::dvec2 f = evaluator.force_rt(hand, 1.0 / rate_hz);
    EXPECT_TRUE(std::isfinite(f.x) && std::isfinite(f.y));
    const double e = energy();
    trace.min_J = std::min(trace.min_J, e);
    trace.max_J = std::max(trace.max_J, e);
    if (k <= second) trace.first_second_mean_J += e / second;
    if (k > ticks - second) trace.last_second_mean_J += e / second;
  }
  return trace;
}

// The brick on a spring: 0.5 kg on 100 N/m (2.25 Hz), a 1 cm step of the hand, no damping at all.
TEST(PointMasses, UndampedLinkKeepsItsEnergyFor10sAtEveryServoRate) {
  const auto brick = one_mass(0.5, 100, 0, 0);
  for (double rate : {900.0, 1000.0, 10000.0}) {
    SCOPED_TRACE(rate);
    const EnergyTrace e = swing_energy(brick, rate, 10.0, {0.01, 0.0});
    EXPECT_NEAR(e.initial_J, 0.5 * 100 * 0.01 * 0.01, 1e-12);
    EXPECT_LE(e.max_J, 1.01 * e.initial_J);
    EXPECT_GE(e.min_J, 0.99 * e.initial_J);
  }
}

// The stiff light mass: 5 g on 2000 N/m (100 Hz) at 900 Hz needs 3 substeps. Semi-implicit Euler's
// energy swings by up to about h omega / 2 within an oscillation (h omega = 0.234 here) but does not
// drift: the mean over the last second matches the first.
TEST(PointMasses, StiffLightMassIsStableAt900Hz) {
  const auto light = one_mass(0.005, 2000, 0, 0);
  EXPECT_EQ(PatchEvaluator::substeps_for(light, 1.0 / 900), 3u);  // ceil(632.5 rad/s / 900 Hz / 0.25)
  const double h_omega = std::sqrt(2000 / 0.005) / 900 / 3;
  const EnergyTrace e = swing_energy(light, 900, 10.0, {0.005, -0.003});
  EXPECT_LE(e.max_J, (1 + 0.6 * h_omega) * e.initial_J);
  EXPECT_GE(e.min_J, (1 - 0.6 * h_omega) * e.initial_J);
  EXPECT_NEAR(e.last_second_mean_J, e.first_second_mean_J, 0.01 * e.first_second_mean_J);
  // With the same mass damped it settles: energy only leaves.
  const EnergyTrace damped = swing_energy(one_mass(0.005, 2000, 0.5, 0), 900, 10.0, {0.005, -0.003});
  EXPECT_LE(damped.max_J, damped.initial_J * (1 + 1e-12));
  EXPECT_LT(damped.last_second_mean_J, 1e-6 * damped.initial_J);
}

TEST(PointMasses, SubstepsFollowTheFastestRate) {
  // One mass: omega = sqrt(k / m), damping rate (c + cg) / m.
  const auto spring_bound = one_mass(0.01, 1000, 0.0, 0.0);  // omega 316.2 rad/s
  EXPECT_EQ(PatchEvaluator::substeps_for(spring_bound, 1e-3), 2u);    // 0.3162 / 0.25 = 1.26
  EXPECT_EQ(PatchEvaluator::substeps_for(spring_bound, 1e-4), 1u);
  EXPECT_EQ(PatchEvaluator::substeps_for(spring_bound, 0.0), 0u);
  const auto damper_bound = one_mass(0.01, 1, 3.0, 2.0);  // (3 + 2) / 0.01 = 500 /s
  EXPECT_EQ(PatchEvaluator::substeps_for(damper_bound, 1e-3), 1u);    // 0.5 / 0.5 = 1
  EXPECT_EQ(PatchEvaluator::substeps_for(damper_bound, 1.1e-3), 2u);
  // Two masses: omega^2 is the larger root of m0 m1 w^4 - (m1 (k0 + k1) + m0 k1) w^2 + k0 k1 = 0.
  const auto chain = two_masses(0.02, 0.01, 400, 300, 0, 0, 0);
  const double b = (0.01 * 700 + 0.02 * 300) / (0.02 * 0.01), c = 400.0 * 300 / (0.02 * 0.01);
  const double omega = std::sqrt((b + std::sqrt(b * b - 4 * c)) / 2);
  EXPECT_EQ(PatchEvaluator::substeps_for(chain, 1.0 / 900), static_cast<std::uint32_t>(std::ceil(omega / 900 / 0.25)));
  // Nothing to integrate stiffly: one substep.
  EXPECT_EQ(PatchEvaluator::substeps_for(one_mass(0.1, 0, 0, 0), 1e-3), 1u);
  // Above the cap the count is still reported, for the compiler to refuse: omega = 31623 rad/s,
  // 31623 / 900 / 0.25 = 140.5.
  EXPECT_EQ(PatchEvaluator::substeps_for(one_mass(0.001, 1e6, 0, 0), 1.0 / 900), 141u);
}

// A tick far longer than 64 substeps allow (a stall) runs 64 of the largest stable substep: the
// masses fall behind the clock but stay bounded.
TEST(PointMasses, BeyondTheSubstepCapTheMassesLoseTimeNotStability) {
  const auto light = one_mass(0.005, 2000, 0, 0);
  ASSERT_GT(PatchEvaluator::substeps_for(light, 0.5), kMaxPointMassSubsteps);
  const EnergyTrace e = swing_energy(light, 2.0, 50.0, {0.005, 0.0});  // 0.5 s per tick
  EXPECT_LE(e.max_J, 1.2 * e.initial_J);
  EXPECT_GE(e.min_J, 0.8 * e.initial_J);
}

// Reset hangs the masses at rest under gravity: the hand feels their whole weight at once, and
// holding still keeps them there.
TEST(PointMasses, ResetHangsTheMassesAtRest) {
  const auto chain = two_masses(0.3, 0.2, 150, 80, 0.5, 0.4, 0.1, 0.0, -9.81);
  const auto program = program_of({chain});
  PatchEvaluator evaluator(program);
  HandState hand;
  hand.position_m = {0.01, 0.02};
  evaluator.reset_rt(hand);
  const TermState& s = *evaluator.state_of(0);
  EXPECT_NEAR(s.masses.position_m[0].y, 0.02 - 0.5 * 9.81 / 150, 1e-12);
  EXPECT_NEAR(s.masses.position_m[1].y, 0.02 - 0.5 * 9.81 / 150 - 0.2 * 9.81 / 80, 1e-12);
  for (int k = 0; k < 2000; ++k) {
    const glm::dvec2 f = evaluator.force_rt(hand, k == 0 ? 0.0 : 1e-3);
    ASSERT_NEAR(f.x, 0.0, 1e-9);
    ASSERT_NEAR(f.y, -(0.3 + 0.2) * 9.81, 1e-9);
  }
}

}  // namespace
}  // namespace sandpaper::runtime
