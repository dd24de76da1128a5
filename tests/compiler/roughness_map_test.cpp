// The calibrated roughness map and named levels, against the numbers issue 2 and the thesis give.
#include <cmath>

#include <gtest/gtest.h>

#include "test_support.hpp"

using namespace sandpaper;

TEST(RoughnessMap, RatioScaleMatchesFigure19) {
  const auto& map = test::shipped_compiler().calibration().roughness_map();
  EXPECT_EQ(map.id, "minsky1995-fig19");
  EXPECT_NEAR(map.slope, 0.76, 0.001);
  EXPECT_NEAR(*map.intercept, -0.51, 0.005);
  EXPECT_NEAR(map.reference_si, 3.746, 0.0005);     // 382 gf
  EXPECT_NEAR(map.value_for(1.0), 3.746, 0.0005);
  EXPECT_NEAR(map.value_for(0.6), 1.912, 0.001);         // issue 2: "roughness 0.6 is 1.912 N"
  EXPECT_NEAR(map.percept_of(18 * 9.80665e-3), 0.098, 0.0005);  // issue 2: 0.098 at 18 gf
  EXPECT_DOUBLE_EQ(map.percept_of(0), 0);
  for (double r : {0.1, 0.33, 0.7, 1.0, 1.5}) EXPECT_NEAR(map.percept_of(map.value_for(r)), r, 1e-12);
  EXPECT_NEAR(map.period->min, 0.0007, 1e-12);
  EXPECT_NEAR(map.period->max, 0.010, 1e-12);
}

TEST(RoughnessMap, DoublingForceGivesTwoToThePowerSlope) {
  const auto& map = test::shipped_compiler().calibration().roughness_map();
  EXPECT_NEAR(map.percept_of(2.0) / map.percept_of(1.0), std::pow(2.0, 0.759593), 1e-12);
}

TEST(RoughnessLevels, EqualStepsInForceJNDsAcrossTheCalibratedRange) {
  const auto& cal = test::shipped_compiler().calibration();
  const auto& map = cal.roughness_map();
  const auto& levels = cal.roughness_levels();
  ASSERT_EQ(levels.size(), 5u);
  EXPECT_NEAR(map.value_for(levels.front().value), 18 * 9.80665e-3, 0.001);
  EXPECT_NEAR(levels.back().value, 1.0, 1e-12);
  // Steps of ln(382/18)/4 in log force: 6.48 JNDs of 12.5 % each.
  double step = std::log(382.0 / 18.0) / 4;
  for (std::size_t i = 1; i < levels.size(); ++i) {
    double s = std::log(map.value_for(levels[i].value) / map.value_for(levels[i - 1].value));
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
    // An empty directory: every missing part is named, in one report.
    EXPECT_NE(std::string(e.what()).find("no map with percept = \"roughness\""), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("force-jnd.toml"), std::string::npos) << e.what();
  }
}
