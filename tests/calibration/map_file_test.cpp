// The written map file: TOML in the documented format, its numbers those of the fit.
#include <cmath>

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include "sandpaper/calibration/fit.hpp"
#include "sandpaper/calibration/fit_error.hpp"
#include "synthetic.hpp"

using namespace sandpaper::calibration;

namespace {

double quantity_N(const std::string& s) {  // "3.74612 N"
  EXPECT_EQ(s.substr(s.size() - 2), " N") << s;
  return std::stod(s);
}

}  // namespace

TEST(MapFile, HoldsTheFit) {
  const auto fit = fit_magnitude_estimation(synthetic::simulate_experiment({}).data);
  const auto doc = toml::parse(map_file_text(fit, compile_map_options("test-map")));
  EXPECT_EQ(doc["schema"].value_or(std::string()), "sandpaper-map/1");
  EXPECT_EQ(doc["id"].value_or(std::string()), "test-map");
  EXPECT_EQ(doc["percept"].value_or(std::string()), "roughness");
  EXPECT_EQ(doc["status"].value_or(std::string()), "measured");
  EXPECT_EQ(doc["use"].value_or(std::string()), "compile");
  EXPECT_EQ(doc["law"].value_or(std::string()), "log-linear");
  const auto* preds = doc["predictor"].as_array();
  ASSERT_TRUE(preds && preds->size() == 1);
  const auto& p = *preds->get(0)->as_table();
  EXPECT_EQ(p["name"].value_or(std::string()), "force");
  EXPECT_EQ(p["unit"].value_or(std::string()), "N");
  const auto& s = fit.force.coefficient("log force");
  EXPECT_NEAR(p["coefficient"].value_or(0.0), s.value, 1e-5 * std::abs(s.value));
  EXPECT_NEAR(p["se"].value_or(0.0), s.se, 1e-5 * s.se);
  EXPECT_NEAR(p["t"].value_or(0.0), s.t, 1e-3 * std::abs(s.t));
  EXPECT_NEAR(doc["intercept"]["value"].value_or(0.0), fit.intercept(), 1e-5 * std::abs(fit.intercept()));
  EXPECT_NEAR(doc["intercept"]["se"].value_or(0.0), fit.force.coefficient("constant").se, 1e-5);
  EXPECT_NEAR(doc["fit"]["r_squared"].value_or(0.0), fit.force.r_squared, 1e-5);
  EXPECT_NEAR(doc["fit"]["r_squared_adjusted"].value_or(0.0), fit.force.r_squared_adjusted, 1e-5);
  EXPECT_NEAR(doc["fit"]["residual_sd"].value_or(0.0), fit.force.s, 1e-6);
  EXPECT_EQ(doc["fit"]["degrees_of_freedom"].value_or(0), 28);
  EXPECT_NEAR(doc["fit"]["f_ratio"].value_or(0.0), fit.force.f_ratio, 1e-4 * fit.force.f_ratio);
  EXPECT_EQ(doc["fit"]["stimuli"].value_or(0), 30);
  EXPECT_EQ(doc["fit"]["subjects"].value_or(0), 15);
  EXPECT_EQ(doc["fit"]["runs"].value_or(0), 4);
  EXPECT_NE(doc["fit"]["normalisation"].value_or(std::string()).find("geometric mean"), std::string::npos);
  // Ratio scale at the strongest stimulus (194 program units, 3.746 N); the domain holds every stimulus.
  const double fmax = 194 * synthetic::kNewtonsPerProgramUnit, fmin = 9 * synthetic::kNewtonsPerProgramUnit;
  EXPECT_EQ(doc["ratio_scale"]["predictor"].value_or(std::string()), "force");
  EXPECT_NEAR(quantity_N(doc["ratio_scale"]["reference"].value_or(std::string())), fmax, 1e-5);
  const auto* force = doc["domain"]["force"].as_array();
  ASSERT_TRUE(force && force->size() == 2);
  EXPECT_LE(quantity_N(force->get(0)->value_or(std::string())), fmin);
  EXPECT_GE(quantity_N(force->get(1)->value_or(std::string())), fmax);
  EXPECT_NEAR(quantity_N(force->get(1)->value_or(std::string())), fmax, 1e-5);
  const auto* period = doc["domain"]["period"].as_array();
  ASSERT_TRUE(period && period->size() == 2);
  EXPECT_EQ(period->get(0)->value_or(std::string()), "0.7 mm");
  EXPECT_EQ(period->get(1)->value_or(std::string()), "10 mm");
  EXPECT_NE(doc["source"]["citation"].value_or(std::string()).find(fit.path), std::string::npos);
  EXPECT_TRUE(doc["source"]["where"].is_string());
}

// The CSV's path and the map's id (the output's stem) are bytes on Linux. A name in Latin-1 went into
// the map's comments and [source] as it was, and toml++ then refused the file: every compile with
// that calibration folder failed ("not valid TOML: Encountered invalid utf-8 sequence";
// docs/RELIABILITY.md, F26). Each bad byte is now written as U+FFFD.
TEST(MapFile, APathThatIsNotUtf8StillGivesAMapThatLoads) {
  auto data = synthetic::simulate_experiment({}).data;
  data.path = "/data/m\xfcller/responses.csv";
  const auto fit = fit_magnitude_estimation(data);
  const std::string text = map_file_text(fit, compile_map_options("m\xfcller"));
  const auto doc = toml::parse(text);
  EXPECT_EQ(doc["id"].value_or(std::string()), "m\xef\xbf\xbdller");
  EXPECT_NE(doc["source"]["citation"].value_or(std::string()).find("/data/m\xef\xbf\xbdller/responses.csv"), std::string::npos);
}

// Two subjects, two stimuli each at two forces, whose normalised means balance exactly: the slope
// is 0, and `calibrate fit -o` wrote a map its loader refuses ("a compile map's slope must not be
// zero"; docs/RELIABILITY.md, F33). The fit stands as a report; no map is written from it.
TEST(MapFile, AFitWithSlopeZeroWritesNoMap) {
  const auto data = parse_magnitude_estimation_csv(
      "subject,stimulus,force_N,period_mm,response\nS01,a,1.7331,1.8,2.5\nB,b,0.617562,10,40.6\n"
      "S01,c,1.7331,2.8,2.5\nB,d,0.617562,10,40.7\n",
      "z.csv");
  const auto fit = fit_magnitude_estimation(data);
  ASSERT_EQ(fit.slope(), 0.0);
  try {
    (void)map_file_text(fit, compile_map_options("z"));
    FAIL() << "a map with slope 0 was written";
  } catch (const FitError& e) {
    EXPECT_NE(std::string(e.what()).find("the fitted slope is 0"), std::string::npos) << e.what();
  }
}

