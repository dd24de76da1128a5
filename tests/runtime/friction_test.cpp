// Coulomb friction with stick-slip (schema::FrictionTerm; Karnopp 1985, Hayward & Armstrong 2000):
// a spring to an adhesion point that breaks loose at mu_static P and slides at mu_kinetic P.
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "term_samples.hpp"

using namespace sandpaper::runtime;
using namespace sandpaper::runtime::testing;

namespace {

constexpr double kMuS = 0.8, kMuK = 0.5, kPress = 2.0, kK = 2000, kDt = 1e-3;

struct Drive {
  PatchEvaluator ev;
  HandState hand;
  glm::dvec2 last_force{0, 0};
  explicit Drive(const sandpaper::schema::PatchProgram& p) : ev(p) { ev.reset_rt(hand); }
  // Moves the hand to `p` over one tick and returns the force there.
  glm::dvec2 to(glm::dvec2 p) {
    hand.velocity_m_s = (p - hand.position_m) / kDt;
    hand.position_m = p;
    last_force = ev.force_rt(hand, kDt);
    return last_force;
  }
};

}  // namespace

TEST(Friction, SticksLikeASpringThenSlidesAtTheKineticForce) {
  const auto program = program_of({friction(kMuS, kMuK, kPress, kK)});
  Drive d(program);
  const double z_static = kMuS * kPress / kK;  // 0.8 mm
  // Stuck: the force is the presliding spring, -k x, up to mu_s P.
  for (double x = 0; x < 0.9 * z_static; x += 10e-6) EXPECT_NEAR(d.to({x, 0}).x, -kK * x, 1e-9) << x;
  // At 20 mm/s it breaks loose past 0.8 mm and slides at mu_k P = 1 N, opposing the motion.
  double peak = 0;
  for (int i = 0; i < 500; ++i) {
    const double f = -d.to({d.hand.position_m.x + 20e-6, 0}).x;
    peak = std::max(peak, f);
  }
  EXPECT_LE(peak, kMuS * kPress + kK * 20e-6);  // never more than the breakaway force (plus one tick's travel)
  EXPECT_GE(peak, kMuS * kPress - kK * 20e-6);
  EXPECT_NEAR(d.last_force.x, -kMuK * kPress, 1e-9);
  EXPECT_NEAR(d.last_force.y, 0, 1e-12);
  const auto* s = d.ev.state_of(0);
  ASSERT_NE(s, nullptr);
  EXPECT_FALSE(s->sticking);
}

// Stopped, the contact sticks again: moving on needs the static force once more (stick-slip).
TEST(Friction, StoppingRestoresStaticFriction) {
  const auto program = program_of({friction(kMuS, kMuK, kPress, kK)});
  Drive d(program);
  for (int i = 0; i < 200; ++i) d.to({d.hand.position_m.x + 20e-6, 0});
  ASSERT_NEAR(-d.last_force.x, kMuK * kPress, 1e-9);
  d.to(d.hand.position_m);  // held still: below the stick speed
  EXPECT_TRUE(d.ev.state_of(0)->sticking);
  double peak = 0;
  for (int i = 0; i < 200; ++i) peak = std::max(peak, -d.to({d.hand.position_m.x + 20e-6, 0}).x);
  EXPECT_GT(peak, kMuK * kPress + 0.5 * (kMuS - kMuK) * kPress);  // broke loose again at about mu_s P
  // Turning back: the contact sticks and the force reverses through the spring, not at once.
  const double before = d.last_force.x;
  const double after = d.to({d.hand.position_m.x - 20e-6, 0}).x;
  EXPECT_NEAR(after - before, kK * 20e-6, 1e-9);
}

// Passive: along any path the contact takes energy from the hand and at most gives back what its spring
// holds. With the force of the position reached, the work it does on the hand over a path from rest is
// at most minus the energy its spring holds at the end (the adhesion point only moves toward the hand,
// so its moves release energy and never add any).
namespace {

// Drives `program` (one friction-like term) along 20 random paths from rest and checks each: the work
// done on the hand is at most minus the energy the presliding spring holds at the end, and the path
// did break loose (the slip branch was exercised).
void expect_passive_on_random_paths(const sandpaper::schema::PatchProgram& program, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> jerk(0, 4.0);
  for (int trial = 0; trial < 20; ++trial) {
    Drive d(program);
    glm::dvec2 v{0, 0};
    double work_on_hand = 0;
    int slides = 0;
    for (int i = 0; i < 5000; ++i) {
      v += glm::dvec2{jerk(rng), jerk(rng)} * kDt;
      v *= 0.995;
      const glm::dvec2 before = d.hand.position_m;
      const glm::dvec2 f = d.to(before + v * kDt);
      work_on_hand += glm::dot(f, d.hand.position_m - before);
      slides += d.ev.state_of(0)->sticking ? 0 : 1;
    }
    const glm::dvec2 z = d.hand.position_m - d.ev.state_of(0)->adhesion_m;
    const double stored = 0.5 * kK * glm::dot(z, z);
    EXPECT_LE(work_on_hand, -stored + 1e-12) << trial;
    EXPECT_GT(slides, 0) << trial;
  }
}

}  // namespace

TEST(Friction, NeverGivesTheHandEnergy) {
  expect_passive_on_random_paths(program_of({friction(kMuS, kMuK, kPress, kK, 0.002)}), 15);
}

// Nap friction (schema::NapFrictionTerm): the same stick band, its coefficients set by the way the hand
// pulls from the adhesion point. With the nap lying toward +y: stroking toward +y slides at mu_k P,
// toward -y at the against coefficient, across the nap (along x) halfway between.
TEST(NapFriction, SlidesWithTheNapAtKineticAndAgainstItAtTheAgainstCoefficient) {
  constexpr double kWithS = 0.3, kWithK = 0.2, kAgainstS = 0.9, kAgainstK = 0.6;
  const auto program = program_of({nap_friction(kWithS, kWithK, kAgainstS, kAgainstK, kPress)});
  struct Way {
    glm::dvec2 step;
    double kinetic, breakaway;
  };
  const double half_k = 0.5 * (kWithK + kAgainstK), half_s = 0.5 * (kWithS + kAgainstS);
  for (const Way& way : {Way{{0, 20e-6}, kWithK, kWithS}, Way{{0, -20e-6}, kAgainstK, kAgainstS},
                         Way{{20e-6, 0}, half_k, half_s}, Way{{-20e-6, 0}, half_k, half_s}}) {
    SCOPED_TRACE(way.step.x + way.step.y);
    Drive d(program);
    double peak = 0;
    for (int i = 0; i < 600; ++i) peak = std::max(peak, glm::length(d.to(d.hand.position_m + way.step)));
    // Sliding: mu_k P against the stroke.
    EXPECT_NEAR(glm::length(d.last_force), way.kinetic * kPress, 1e-9);
    EXPECT_LT(glm::dot(d.last_force, way.step), 0);
    EXPECT_FALSE(d.ev.state_of(0)->sticking);
    // Breaking loose: mu_s P, within one tick's travel.
    EXPECT_NEAR(peak, way.breakaway * kPress, kK * 20e-6 + 1e-12);
  }
}

// With equal coefficients both ways, nap friction is friction: the same forces tick by tick.
TEST(NapFriction, EqualCoefficientsPlayAsFriction) {
  const auto plain_program = program_of({friction(kMuS, kMuK, kPress, kK)});
  const auto nap_program = program_of({nap_friction(kMuS, kMuK, kMuS, kMuK, kPress, 0.3, kK)});
  Drive plain(plain_program);
  Drive nap(nap_program);
  std::mt19937 rng(7);
  std::normal_distribution<double> jerk(0, 4.0);
  glm::dvec2 v{0, 0};
  for (int i = 0; i < 3000; ++i) {
    v += glm::dvec2{jerk(rng), jerk(rng)} * kDt;
    const glm::dvec2 p = plain.hand.position_m + v * kDt;
    const glm::dvec2 a = plain.to(p), b = nap.to(p);
    ASSERT_NEAR(a.x, b.x, 1e-12) << i;
    ASSERT_NEAR(a.y, b.y, 1e-12) << i;
  }
}

// Passive as friction is: the adhesion point only moves toward the hand, whichever coefficients apply.
TEST(NapFriction, NeverGivesTheHandEnergy) {
  expect_passive_on_random_paths(program_of({nap_friction(0.3, 0.2, 0.9, 0.6, kPress, 1.2, kK, 0.002)}), 18);
}
