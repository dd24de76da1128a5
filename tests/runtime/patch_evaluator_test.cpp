#include "sandpaper/runtime/patch_evaluator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "runtime_test_support.hpp"

namespace sandpaper::runtime {
namespace {

using testing::damper;
using testing::grating;
using testing::program_of;
using testing::spring;

HandState at(double x, double y, glm::dvec2 velocity = {0, 0}) {
  HandState hand;
  hand.position_m = {x, y};
  hand.velocity_m_s = velocity;
  return hand;
}

TEST(PatchEvaluator, SpringPullsTowardItsCentre) {
  const auto program = program_of({spring(200.0, 0.01, -0.02)});
  const glm::dvec2 f = PatchEvaluator(program).force_rt(at(0.03, 0.01), 1e-3);
  EXPECT_NEAR(f.x, -200.0 * (0.03 - 0.01), 1e-12);
  EXPECT_NEAR(f.y, -200.0 * (0.01 + 0.02), 1e-12);
}

TEST(PatchEvaluator, DamperOpposesVelocityAndIgnoresPosition) {
  const auto program = program_of({damper(3.0)});
  PatchEvaluator evaluator(program);
  const glm::dvec2 f = evaluator.force_rt(at(0.02, -0.01, {0.1, -0.2}), 1e-3);
  EXPECT_NEAR(f.x, -0.3, 1e-15);
  EXPECT_NEAR(f.y, 0.6, 1e-15);
  const glm::dvec2 g = evaluator.force_rt(at(-0.04, 0.03, {0.1, -0.2}), 1e-3);
  EXPECT_EQ(f, g);
}

TEST(PatchEvaluator, TermsAreSummed) {
  const auto program = program_of({spring(100.0), damper(2.0), spring(50.0, 0.01, 0.0)});
  const glm::dvec2 f = PatchEvaluator(program).force_rt(at(0.02, 0.01, {0.5, 0.25}), 1e-3);
  EXPECT_NEAR(f.x, -100.0 * 0.02 - 2.0 * 0.5 - 50.0 * 0.01, 1e-12);
  EXPECT_NEAR(f.y, -100.0 * 0.01 - 2.0 * 0.25 - 50.0 * 0.01, 1e-12);
}

TEST(PatchEvaluator, OutsideThePatchRectangleThereIsNoForce) {
  auto program = program_of({spring(1000.0), damper(5.0), grating(0.004, 0, {1.0f, 2.0f})});
  program.size_m[0] = 0.08;
  program.size_m[1] = 0.04;
  PatchEvaluator evaluator(program);
  EXPECT_EQ(evaluator.force_rt(at(0.0401, 0.0, {1, 1}), 1e-3), glm::dvec2(0, 0));
  EXPECT_EQ(evaluator.force_rt(at(-0.0401, 0.0, {1, 1}), 1e-3), glm::dvec2(0, 0));
  EXPECT_EQ(evaluator.force_rt(at(0.0, 0.0201, {1, 1}), 1e-3), glm::dvec2(0, 0));
  EXPECT_EQ(evaluator.force_rt(at(0.0, -0.0201, {1, 1}), 1e-3), glm::dvec2(0, 0));
  // Just inside the narrower (y) edge the patch still pushes.
  EXPECT_NE(evaluator.force_rt(at(0.0, 0.0199, {1, 1}), 1e-3), glm::dvec2(0, 0));
}

TEST(PatchEvaluator, NonFinitePositionGivesNonFiniteForce) {
  const auto program = program_of({spring(10.0)});
  const glm::dvec2 f = PatchEvaluator(program).force_rt(at(std::numeric_limits<double>::quiet_NaN(), 0.0), 1e-3);
  EXPECT_TRUE(std::isnan(f.x) && std::isnan(f.y));
}

void construct(const schema::PatchProgram& program) { PatchEvaluator evaluator(program); }

TEST(PatchEvaluator, ConstructionRejectsShapesTheTickCannotIndex) {
  EXPECT_THROW(construct(program_of({grating(0.0, 0, {1.0f, 2.0f})})), std::invalid_argument);
  EXPECT_THROW(construct(program_of({grating(-0.001, 0, {1.0f, 2.0f})})), std::invalid_argument);
  EXPECT_THROW(construct(program_of({grating(0.001, 0, {1.0f})})), std::invalid_argument);
  schema::HeightFieldTerm field;
  field.nx = 2;
  field.ny = 2;
  field.spacing_m[0] = field.spacing_m[1] = 0.001;
  field.force_x_N = {0, 0, 0, 0};
  field.force_y_N = {0, 0, 0};
  EXPECT_THROW(construct(program_of({field})), std::invalid_argument);
  field.force_y_N = {0, 0, 0, 0};
  EXPECT_NO_THROW(construct(program_of({field})));
  field.spacing_m[1] = 0;
  EXPECT_THROW(construct(program_of({field})), std::invalid_argument);
}

}  // namespace
}  // namespace sandpaper::runtime
