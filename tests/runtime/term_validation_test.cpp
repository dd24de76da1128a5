// The evaluator refuses, before the first tick, every parameter the tick would divide by, index
// with, or integrate unstably.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "term_samples.hpp"

namespace sandpaper::runtime {
namespace {

using namespace testing;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

void construct(const schema::PatchProgram& program) { PatchEvaluator evaluator(program); }
void construct(const schema::Term& term) { construct(program_of({term})); }

TEST(TermValidation, EveryKindsSampleIsAccepted) {
  EXPECT_NO_THROW(construct(program_of(every_term_kind())));
}

TEST(TermValidation, NonFiniteParametersAreRefused) {
  EXPECT_THROW(construct(spring(kNaN)), std::invalid_argument);
  EXPECT_THROW(construct(damper(kInf)), std::invalid_argument);
  EXPECT_THROW(construct(constant_force(0, kNaN)), std::invalid_argument);
  EXPECT_THROW(construct(nap(kNaN)), std::invalid_argument);
  EXPECT_THROW(construct(periodic(schema::PeriodicShape::Sine, kInf, 0.01)), std::invalid_argument);
  EXPECT_THROW(construct(ridge(kNaN, 0.01, 0.002)), std::invalid_argument);
  EXPECT_THROW(construct(ridge(100, 0.01, kNaN)), std::invalid_argument);
  EXPECT_THROW(construct(bowl(kNaN, 0.03)), std::invalid_argument);
  EXPECT_THROW(construct(linear_field(0, kInf)), std::invalid_argument);
  EXPECT_THROW(construct(linear_spring(100, kNaN, 0, 0)), std::invalid_argument);
  EXPECT_THROW(construct(linear_spring(100, 0, kNaN, 0)), std::invalid_argument);
  EXPECT_THROW(construct(minus(kNaN, 0.02)), std::invalid_argument);
  EXPECT_THROW(construct(follower_spring(kInf, 0.1)), std::invalid_argument);
  EXPECT_THROW(construct(one_mass(0.1, 100, 0.1, 0, kNaN)), std::invalid_argument);
  EXPECT_THROW(construct(attractor(50, 0.02, 1, kNaN)), std::invalid_argument);
  EXPECT_THROW(construct(attractor(50, 0.02, 1, 0, kInf)), std::invalid_argument);
}

TEST(TermValidation, DivisorsMustBePositive) {
  for (double bad : {0.0, -0.01}) {
    EXPECT_THROW(construct(periodic(schema::PeriodicShape::Triangle, 1, bad)), std::invalid_argument);
    EXPECT_THROW(construct(ridge(100, bad, 0.002)), std::invalid_argument);
    EXPECT_THROW(construct(bowl(100, bad)), std::invalid_argument);
    EXPECT_THROW(construct(follower_spring(100, bad)), std::invalid_argument);
    EXPECT_THROW(construct(attractor(50, 0.02, bad, 0)), std::invalid_argument);
  }
  EXPECT_THROW(construct(attractor(50, 0.02, 1, -1)), std::invalid_argument);  // 1 + swirl = 0
  EXPECT_THROW(construct(attractor(50, -0.02, 1, 0)), std::invalid_argument);
  EXPECT_NO_THROW(construct(attractor(50, 0.0, 1, -0.5)));
  EXPECT_THROW(construct(minus(100, -0.01)), std::invalid_argument);
  EXPECT_NO_THROW(construct(minus(100, 0.0)));
  auto shape = periodic(schema::PeriodicShape::Sine, 1, 0.01);
  shape.shape = static_cast<schema::PeriodicShape>(7);
  EXPECT_THROW(construct(shape), std::invalid_argument);
}

TEST(TermValidation, PointMassesMustBeAPhysicalChain) {
  auto chain = two_masses(0.1, 0.05, 100, 50, 0.2, 0.1, 0.05);
  EXPECT_NO_THROW(construct(chain));
  for (std::uint32_t count : {0u, 3u}) {
    auto bad = chain;
    bad.count = count;
    EXPECT_THROW(construct(bad), std::invalid_argument);
  }
  for (int i = 0; i < 2; ++i) {
    auto massless = chain;
    massless.mass_kg[i] = 0;
    EXPECT_THROW(construct(massless), std::invalid_argument);
    auto pushing = chain;
    pushing.stiffness_N_per_m[i] = -10;
    EXPECT_THROW(construct(pushing), std::invalid_argument);
    auto pumping = chain;
    pumping.damping_Ns_per_m[i] = -0.1;
    EXPECT_THROW(construct(pumping), std::invalid_argument);
  }
  auto ground = chain;
  ground.ground_damping_Ns_per_m = -0.1;
  EXPECT_THROW(construct(ground), std::invalid_argument);
  // One mass: the second slot is not looked at.
  auto one = one_mass(0.1, 100, 0.2);
  one.mass_kg[1] = -5;
  EXPECT_NO_THROW(construct(one));
  EXPECT_THROW(construct(follower_spring(-100, 0.1)), std::invalid_argument);
}

TEST(TermValidation, EnergyFieldsMustBeNonNegative) {
  auto program = program_of({damper(-1)});
  program.energy_budget_J = -0.001;
  EXPECT_THROW(construct(program), std::invalid_argument);
  program.energy_budget_J = 0.001;
  program.energy_refill_W = kNaN;
  EXPECT_THROW(construct(program), std::invalid_argument);
  program.energy_refill_W = 0;
  EXPECT_NO_THROW(construct(program));
}

TEST(TermValidation, TheMessageNamesTheTermAndParameter) {
  try {
    construct(program_of({spring(10), follower_spring(100, 0)}));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "term 1 (follower spring): lag must be positive and finite");
  }
}

}  // namespace
}  // namespace sandpaper::runtime
