// Height fields: bilinear interpolation of the lateral-force grid; zero off the grid unless it repeats.
#include <gtest/gtest.h>

#include <cstddef>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"

namespace sandpaper::runtime {
namespace {

using testing::program_of;

constexpr double kTol = 1e-12;

// 3 x 2 samples, no two alike, spacing unequal on the axes so x/y mix-ups show.
schema::HeightFieldTerm small_field(bool repeat) {
  schema::HeightFieldTerm field;
  field.nx = 3;
  field.ny = 2;
  field.origin_m[0] = -0.010;
  field.origin_m[1] = -0.004;
  field.spacing_m[0] = 0.008;
  field.spacing_m[1] = 0.005;
  field.repeat = repeat;
  field.force_x_N = {1.0f, 2.0f, 4.0f, -1.0f, 0.5f, 3.0f};
  field.force_y_N = {-2.0f, 0.25f, 1.0f, 6.0f, -3.0f, 0.75f};
  return field;
}

double sample(const std::vector<float>& grid, std::size_t ix, std::size_t iy) { return grid[iy * 3 + ix]; }

glm::dvec2 grid_point(const schema::HeightFieldTerm& field, double gx, double gy) {
  return {field.origin_m[0] + gx * field.spacing_m[0], field.origin_m[1] + gy * field.spacing_m[1]};
}

glm::dvec2 force_at(PatchEvaluator evaluator, glm::dvec2 p) {
  HandState hand;
  hand.position_m = p;
  return evaluator.force_rt(hand, 1e-3);
}

TEST(HeightField, SamplesAreReproducedAtTheirPoints) {
  const auto field = small_field(false);
  const auto program = program_of({field});
  PatchEvaluator evaluator(program);
  for (std::size_t iy = 0; iy < 2; ++iy)
    for (std::size_t ix = 0; ix < 3; ++ix) {
      SCOPED_TRACE(::testing::Message() << "sample " << ix << "," << iy);
      const glm::dvec2 f =
          force_at(evaluator, grid_point(field, static_cast<double>(ix), static_cast<double>(iy)));
      EXPECT_NEAR(f.x, sample(field.force_x_N, ix, iy), kTol);
      EXPECT_NEAR(f.y, sample(field.force_y_N, ix, iy), kTol);
    }
}

TEST(HeightField, CellCentreIsTheMeanOfItsCorners) {
  const auto field = small_field(false);
  const auto program = program_of({field});
  PatchEvaluator evaluator(program);
  for (std::size_t ix = 0; ix < 2; ++ix) {
    SCOPED_TRACE(ix);
    const auto mean = [&](const std::vector<float>& g) {
      return (sample(g, ix, 0) + sample(g, ix + 1, 0) + sample(g, ix, 1) + sample(g, ix + 1, 1)) / 4.0;
    };
    const glm::dvec2 f = force_at(evaluator, grid_point(field, static_cast<double>(ix) + 0.5, 0.5));
    EXPECT_NEAR(f.x, mean(field.force_x_N), kTol);
    EXPECT_NEAR(f.y, mean(field.force_y_N), kTol);
  }
}

TEST(HeightField, BilinearOffCentre) {
  const auto field = small_field(false);
  const auto program = program_of({field});
  // At (0.25, 0.75) of cell (1, 0): weights (1-fx)(1-fy), fx(1-fy), (1-fx)fy, fx fy.
  const double fx = 0.25, fy = 0.75;
  const auto expected = [&](const std::vector<float>& g) {
    return (1 - fx) * (1 - fy) * sample(g, 1, 0) + fx * (1 - fy) * sample(g, 2, 0) + (1 - fx) * fy * sample(g, 1, 1) +
           fx * fy * sample(g, 2, 1);
  };
  const glm::dvec2 f = force_at(PatchEvaluator(program), grid_point(field, 1.0 + fx, fy));
  EXPECT_NEAR(f.x, expected(field.force_x_N), kTol);
  EXPECT_NEAR(f.y, expected(field.force_y_N), kTol);
}

TEST(HeightField, WithoutRepeatTheFieldEndsAtItsLastSample) {
  const auto field = small_field(false);
  const auto program = program_of({field});
  PatchEvaluator evaluator(program);
  EXPECT_EQ(force_at(evaluator, grid_point(field, -0.01, 0.5)), glm::dvec2(0, 0));
  EXPECT_EQ(force_at(evaluator, grid_point(field, 0.5, -0.01)), glm::dvec2(0, 0));
  EXPECT_EQ(force_at(evaluator, grid_point(field, 2.01, 0.5)), glm::dvec2(0, 0));
  EXPECT_EQ(force_at(evaluator, grid_point(field, 0.5, 1.01)), glm::dvec2(0, 0));
  const glm::dvec2 corner = force_at(evaluator, grid_point(field, 2.0, 1.0));
  EXPECT_NEAR(corner.x, sample(field.force_x_N, 2, 1), kTol);
  EXPECT_NEAR(corner.y, sample(field.force_y_N, 2, 1), kTol);
}

TEST(HeightField, RepeatWrapsWithAPeriodOfTheWholeGrid) {
  const auto field = small_field(true);
  const auto program = program_of({field});
  PatchEvaluator evaluator(program);
  // Beyond the last sample the field blends back toward the first one.
  const glm::dvec2 seam = force_at(evaluator, grid_point(field, 2.5, 0.0));
  EXPECT_NEAR(seam.x, (sample(field.force_x_N, 2, 0) + sample(field.force_x_N, 0, 0)) / 2, kTol);
  EXPECT_NEAR(seam.y, (sample(field.force_y_N, 2, 0) + sample(field.force_y_N, 0, 0)) / 2, kTol);
  // Below the origin: half a cell before sample 0 is the same seam.
  const glm::dvec2 below = force_at(evaluator, grid_point(field, -0.5, 0.0));
  EXPECT_NEAR(below.x, seam.x, kTol);
  EXPECT_NEAR(below.y, seam.y, kTol);
  // Whole grid periods (3 cells in x, 2 in y) change nothing.
  for (double gx : {0.3, 1.7, 2.6})
    for (double gy : {0.2, 1.4}) {
      const glm::dvec2 base = force_at(evaluator, grid_point(field, gx, gy));
      const glm::dvec2 shifted = force_at(evaluator, grid_point(field, gx - 3.0, gy + 2.0));
      EXPECT_NEAR(shifted.x, base.x, 1e-9);
      EXPECT_NEAR(shifted.y, base.y, 1e-9);
    }
  // And where the non-repeating field is silent, the repeating one is not.
  const auto still = program_of({small_field(false)});
  EXPECT_EQ(force_at(PatchEvaluator(still), grid_point(field, 2.5, 0.0)), glm::dvec2(0, 0));
  EXPECT_NE(seam, glm::dvec2(0, 0));
}

}  // namespace
}  // namespace sandpaper::runtime
