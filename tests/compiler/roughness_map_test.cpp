// The calibrated roughness map and named levels, against the numbers issue 2 and the thesis give.
#include <cmath>

#include <gtest/gtest.h>

#include "test_support.hpp"

using namespace sandpaper;

TEST(RoughnessMap, RatioScaleMatchesFigure19) {
  const auto& map = test::shipped_compiler().calibration().roughness_map();
  EXPECT_EQ(map.id, "minsky1995-fig19");
  EXPECT_NEAR(map.slope, 0.76, 0.001);
  EXPECT_NEAR(map.intercept, -0.51, 0.005);
  EXPECT_NEAR(map.reference_force_N, 3.746, 0.0005);     // 382 gf
  EXPECT_NEAR(map.force_for(1.0), 3.746, 0.0005);
  EXPECT_NEAR(map.force_for(0.6), 1.912, 0.001);         // issue 2: "roughness 0.6 is 1.912 N"
  EXPECT_NEAR(map.roughness_of(18 * 9.80665e-3), 0.098, 0.0005);  // issue 2: 0.098 at 18 gf
  EXPECT_DOUBLE_EQ(map.roughness_of(0), 0);
  for (double r : {0.1, 0.33, 0.7, 1.0, 1.5}) EXPECT_NEAR(map.roughness_of(map.force_for(r)), r, 1e-12);
  EXPECT_NEAR(map.domain_period_min_m, 0.0007, 1e-12);
  EXPECT_NEAR(map.domain_period_max_m, 0.010, 1e-12);
}

TEST(RoughnessMap, DoublingForceGivesTwoToThePowerSlope) {
  const auto& map = test::shipped_compiler().calibration().roughness_map();
  EXPECT_NEAR(map.roughness_of(2.0) / map.roughness_of(1.0), std::pow(2.0, 0.759593), 1e-12);
}

TEST(RoughnessLevels, EqualStepsInForceJNDsAcrossTheCalibratedRange) {
  const auto& cal = test::shipped_compiler().calibration();
  const auto& map = cal.roughness_map();
  const auto& levels = cal.roughness_levels();
  ASSERT_EQ(levels.size(), 5u);
  EXPECT_NEAR(map.force_for(levels.front().roughness), 18 * 9.80665e-3, 0.001);
  EXPECT_NEAR(levels.back().roughness, 1.0, 1e-12);
  // Steps of ln(382/18)/4 in log force: 6.48 JNDs of 12.5 % each.
  double step = std::log(382.0 / 18.0) / 4;
  for (std::size_t i = 1; i < levels.size(); ++i) {
    double s = std::log(map.force_for(levels[i].roughness) / map.force_for(levels[i - 1].roughness));
    EXPECT_NEAR(s, step, 0.002) << levels[i].name;
    EXPECT_NEAR(s / std::log(1.125), 6.48, 0.02) << levels[i].name;
    EXPECT_FALSE(levels[i].rationale.empty());
  }
}

TEST(Calibration, BrokenFilesAreReportedWithTheirPath) {
  auto dir = test::temp_dir("cal");
  EXPECT_THROW(calibration::CalibrationSet::load(dir), calibration::CalibrationError);
  try {
    calibration::CalibrationSet::load(dir);
  } catch (const calibration::CalibrationError& e) {
    EXPECT_NE(std::string(e.what()).find("minsky1995-fig19.toml"), std::string::npos);
  }
}
