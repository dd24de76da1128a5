// Fit -> write -> load with the project's calibration loader (schema-validated): the loaded map and
// device are the fitted ones.
#include <filesystem>

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/calibration/device_fit.hpp"
#include "sandpaper/calibration/fit.hpp"
#include "sandpaper/schema/atomic_file.hpp"
#include "synthetic.hpp"

using namespace sandpaper::calibration;

namespace {

std::filesystem::path temp_dir() {
  auto d = std::filesystem::temp_directory_path() /
           ("sandpaper-round-trip-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace

TEST(RoundTrip, FittedMapLoads) {
  const auto e = synthetic::simulate_experiment({});
  const auto fit = fit_magnitude_estimation(e.data);
  const auto dir = temp_dir();
  const auto path = dir / "fitted-roughness.toml";
  sandpaper::schema::write_file_atomically(path, map_file_text(fit, compile_map_options("fitted-roughness")));
  const auto m = load_map_file(path);
  EXPECT_EQ(m.id, "fitted-roughness");
  EXPECT_EQ(m.percept, "roughness");
  EXPECT_TRUE(m.for_compile);
  EXPECT_FALSE(m.provisional);
  EXPECT_EQ(m.ratio_predictor, "force");
  EXPECT_NEAR(m.slope, fit.slope(), 1e-5 * fit.slope());
  EXPECT_NEAR(m.slope_se, fit.slope_se(), 1e-5 * fit.slope_se());
  ASSERT_TRUE(m.intercept.has_value());
  EXPECT_NEAR(*m.intercept, fit.intercept(), 1e-5 * std::abs(fit.intercept()));
  ASSERT_EQ(m.predictors.size(), 1u);
  EXPECT_EQ(m.predictors[0].unit, "N");
  EXPECT_DOUBLE_EQ(m.predictors[0].unit_si, 1.0);
  EXPECT_NEAR(m.reference_si, 194 * synthetic::kNewtonsPerProgramUnit, 1e-5);
  EXPECT_EQ(m.degrees_of_freedom.value_or(0), 28);
  EXPECT_EQ(m.stimuli.value_or(0), 30);
  ASSERT_TRUE(m.force && m.period);
  for (const auto& s : fit.stimuli) {
    EXPECT_TRUE(m.force->contains(s.x, 0)) << s.stimulus;
    EXPECT_TRUE(m.period->contains(s.period_m, 0)) << s.stimulus;
  }
  // The ratio scale: roughness 1 at the strongest stimulus, halving the force scales it by 2^-slope.
  EXPECT_NEAR(m.percept_of(m.reference_si), 1.0, 1e-12);
  EXPECT_NEAR(m.percept_of(m.reference_si / 2), std::pow(0.5, fit.slope()), 1e-5);
  std::filesystem::remove_all(dir);
}

TEST(RoundTrip, CalibratedDeviceLoads) {
  const auto fit = fit_device(synthetic::simulate_gauge({}));
  const auto base_path = std::string(SANDPAPER_SOURCE_DIR) + "/calibration/devices/openffboard-2axis.toml";
  const auto base = toml::parse_file(base_path);
  const auto dir = temp_dir();
  const auto path = dir / "openffboard-2axis.toml";
  sandpaper::schema::write_file_atomically(path, device_file_text(fit, base, {"", base_path, "2026-11-21"}));
  const auto d = load_device_file(path);
  const auto shipped = load_device_file(base_path);
  EXPECT_EQ(d.name, "openffboard-2axis");
  EXPECT_TRUE(d.calibrated());
  EXPECT_FALSE(shipped.calibrated());
  EXPECT_NEAR(d.axis[0].newtons_per_command_unit, fit.axes[0].gain_N_per_unit, 1e-8 * fit.axes[0].gain_N_per_unit);
  EXPECT_NEAR(d.axis[1].newtons_per_command_unit, fit.axes[1].gain_N_per_unit, 1e-8 * fit.axes[1].gain_N_per_unit);
  EXPECT_NEAR(d.command_units(0, 1.0), 1.0 / fit.axes[0].gain_N_per_unit, 1e-3);
  // What the readings cannot give comes from the shipped base.
  EXPECT_EQ(d.command_max, shipped.command_max);
  EXPECT_EQ(d.min_rate_hz, shipped.min_rate_hz);
  EXPECT_EQ(d.max_rate_hz, shipped.max_rate_hz);
  EXPECT_EQ(d.workspace_circle, shipped.workspace_circle);
  EXPECT_DOUBLE_EQ(d.workspace_size_m[0], shipped.workspace_size_m[0]);
  EXPECT_DOUBLE_EQ(d.position_resolution_m, shipped.position_resolution_m);
  // The device cannot command more than command_max x the weaker gain.
  const double reach = static_cast<double>(d.command_max) * std::min(fit.axes[0].gain_N_per_unit, fit.axes[1].gain_N_per_unit);
  EXPECT_LE(d.max_force_N, reach);
  EXPECT_GT(d.max_force_N, 0.999 * reach);
  std::filesystem::remove_all(dir);
}

// Stimuli of one period (a Figure 19 experiment, force only): the map's period domain was written
// ["2.5 mm", "2.5 mm"] and the loader refused it, and with it the calibration folder ("a domain
// range must be positive and ascending"; docs/RELIABILITY.md, F34). A domain of one value loads.
TEST(RoundTrip, AMapFittedAtOnePeriodLoads) {
  auto e = synthetic::simulate_experiment({});
  for (auto& t : e.data.trials) t.period_m = 2.5e-3;
  const auto fit = fit_magnitude_estimation(e.data);
  const auto dir = temp_dir();
  const auto path = dir / "fitted-one-period.toml";
  sandpaper::schema::write_file_atomically(path, map_file_text(fit, compile_map_options("fitted-one-period")));
  const auto m = load_map_file(path);
  ASSERT_TRUE(m.period.has_value());
  EXPECT_DOUBLE_EQ(m.period->min, 2.5e-3);
  EXPECT_DOUBLE_EQ(m.period->max, 2.5e-3);
  EXPECT_TRUE(m.period->contains(2.5e-3));
  EXPECT_FALSE(m.period->contains(3e-3));
  std::filesystem::remove_all(dir);
}

