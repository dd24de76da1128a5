// The shipped examples/calibration/*.csv are exactly what the synthetic generator makes (so their
// '#' header saying how they were made is true), and they fit.
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "examples.hpp"
#include "sandpaper/calibration/device_fit.hpp"
#include "sandpaper/calibration/fit.hpp"

using namespace sandpaper::calibration;

namespace {

std::string read(const std::string& rel) {
  std::ifstream in(std::string(SANDPAPER_SOURCE_DIR) + "/" + rel, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST(Examples, RoughnessResponsesAreTheGeneratorsOutput) {
  const auto text = read("examples/calibration/roughness-responses.csv");
  EXPECT_EQ(text, synthetic::roughness_responses_example())
      << "regenerate with: cmake --build <build> --target update-calibration-examples";
  EXPECT_NE(text.find("SYNTHETIC"), std::string::npos);
  const auto f = fit_magnitude_estimation(parse_magnitude_estimation_csv(text, "roughness-responses.csv"));
  EXPECT_EQ(f.stimuli.size(), 30u);
  EXPECT_EQ(f.subjects.size(), 15u);
  EXPECT_NEAR(f.slope(), 0.76, 3 * f.slope_se() + 0.05);
}

TEST(Examples, OpenffboardReadingsAreTheGeneratorsOutput) {
  const auto text = read("examples/calibration/openffboard-readings.csv");
  EXPECT_EQ(text, synthetic::openffboard_readings_example())
      << "regenerate with: cmake --build <build> --target update-calibration-examples";
  const auto f = fit_device(parse_device_readings_csv(text, "openffboard-readings.csv"));
  ASSERT_EQ(f.axes.size(), 2u);
}
