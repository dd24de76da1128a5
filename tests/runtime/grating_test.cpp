// Gratings: the force is along n = (cos theta, sin theta) and depends only on u = p . n.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"

namespace sandpaper::runtime {
namespace {

using testing::grating;
using testing::program_of;

constexpr double kTol = 1e-9;
const std::vector<float> kTable = {0.5f, 1.5f, -2.0f, 3.0f, -0.25f};  // values chosen so no two neighbours match

glm::dvec2 unit(double angle) { return {std::cos(angle), std::sin(angle)}; }

// Position at grating coordinate u (in periods) plus an offset across the grating that must not matter.
glm::dvec2 at_u(double u, double period, double angle, double across = 0.0) {
  return u * period * unit(angle) + across * unit(angle + std::numbers::pi / 2);
}

glm::dvec2 force_at(PatchEvaluator evaluator, glm::dvec2 p) {
  HandState hand;
  hand.position_m = p;
  return evaluator.force_rt(hand, 1e-3);
}

void expect_force(glm::dvec2 actual, glm::dvec2 expected) {
  EXPECT_NEAR(actual.x, expected.x, kTol);
  EXPECT_NEAR(actual.y, expected.y, kTol);
}

class GratingAtOrientation : public ::testing::TestWithParam<double> {};

TEST_P(GratingAtOrientation, NodesGiveTheTableValueAlongTheNormal) {
  const double angle = GetParam();
  const double period = 0.004;
  const auto program = program_of({grating(period, angle, kTable)});
  PatchEvaluator evaluator(program);
  const double size = static_cast<double>(kTable.size());
  for (std::size_t i = 0; i < kTable.size(); ++i) {
    SCOPED_TRACE(i);
    const double u = static_cast<double>(i) / size;
    expect_force(force_at(evaluator, at_u(u, period, angle)), static_cast<double>(kTable[i]) * unit(angle));
    expect_force(force_at(evaluator, at_u(u, period, angle, 0.013)), static_cast<double>(kTable[i]) * unit(angle));
  }
}

TEST_P(GratingAtOrientation, RepeatsEveryPeriod) {
  const double angle = GetParam();
  const double period = 0.0037;
  const auto program = program_of({grating(period, angle, kTable)});
  PatchEvaluator evaluator(program);
  for (double u : {0.03, 0.27, 0.5, 0.61, 0.93}) {
    SCOPED_TRACE(u);
    const glm::dvec2 base = force_at(evaluator, at_u(u, period, angle));
    expect_force(force_at(evaluator, at_u(u + 1.0, period, angle)), base);
    expect_force(force_at(evaluator, at_u(u + 3.0, period, angle)), base);
    expect_force(force_at(evaluator, at_u(u - 2.0, period, angle)), base);
  }
}

TEST_P(GratingAtOrientation, InterpolatesLinearlyBetweenNodesAndWraps) {
  const double angle = GetParam();
  const double period = 0.005;
  const auto program = program_of({grating(period, angle, kTable)});
  PatchEvaluator evaluator(program);
  const std::size_t size = kTable.size();
  for (std::size_t i = 0; i < size; ++i) {
    SCOPED_TRACE(i);
    const double lo = kTable[i], hi = kTable[(i + 1) % size];
    const double u_mid = (static_cast<double>(i) + 0.5) / static_cast<double>(size);
    expect_force(force_at(evaluator, at_u(u_mid, period, angle)), 0.5 * (lo + hi) * unit(angle));
    const double u_quarter = (static_cast<double>(i) + 0.25) / static_cast<double>(size);
    expect_force(force_at(evaluator, at_u(u_quarter, period, angle)), (0.75 * lo + 0.25 * hi) * unit(angle));
  }
}

INSTANTIATE_TEST_SUITE_P(Orientations, GratingAtOrientation,
                         ::testing::Values(0.0, std::numbers::pi / 2, std::numbers::pi / 6, -2.0));

TEST(Grating, NegativeCoordinatesWrapToTheEndOfTheTable) {
  const auto program = program_of({grating(0.004, 0.0, {0.0f, 1.0f, 2.0f, 3.0f})});
  PatchEvaluator evaluator(program);
  // u = -0.25 is u = 0.75: node 3.
  expect_force(force_at(evaluator, {-0.001, 0.0}), {3.0, 0.0});
  // u = -0.125 is u = 0.875: halfway from node 3 back to node 0.
  expect_force(force_at(evaluator, {-0.0005, 0.0}), {1.5, 0.0});
  // Just below zero is just below a whole period: almost node 0 again, coming from node 3.
  expect_force(force_at(evaluator, {-1e-15, 0.0}), {0.0, 0.0});
  expect_force(force_at(evaluator, {-0.004 - 0.001, 0.0}), {3.0, 0.0});
}

TEST(Grating, VerticalGratingIgnoresX) {
  const auto program = program_of({grating(0.004, std::numbers::pi / 2, {0.0f, 1.0f, 2.0f, 3.0f})});
  PatchEvaluator evaluator(program);
  const glm::dvec2 f = force_at(evaluator, {0.0, 0.002});
  EXPECT_NEAR(f.x, 0.0, kTol);
  EXPECT_NEAR(f.y, 2.0, kTol);
  expect_force(force_at(evaluator, {0.017, 0.002}), f);
}

}  // namespace
}  // namespace sandpaper::runtime
