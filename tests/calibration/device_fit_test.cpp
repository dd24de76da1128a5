// Device calibration from force-gauge readings: the gain is recovered, linearity is reported, and
// the written device file holds the fit and the base's other fields.
#include <cmath>
#include <utility>

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/calibration/device_fit.hpp"
#include "sandpaper/calibration/fit_error.hpp"
#include "synthetic.hpp"

using namespace sandpaper::calibration;

namespace {

// A base in the format of calibration/devices/openffboard-2axis.toml (uncalibrated, 32767 command
// units assumed to give 10 N).
toml::table openffboard_base() {
  return toml::parse(R"toml(schema = "sandpaper-device/1"
name = "openffboard-2axis"
description = "OpenFFBoard 2-axis force-feedback joystick over USB HID PID (uncalibrated)"
command_unit = "HID PID constant-force magnitude"
[force]
max_continuous = "10 N"
command_max = 32767
[force.x]
newtons_per_command_unit = 0.0003051850947599719
command_sense = -1
[force.y]
newtons_per_command_unit = 0.0003051850947599719
command_sense = -1
[position]
resolution = "0.01 mm"
[workspace]
shape = "rectangle"
width = "100 mm"
height = "100 mm"
[usb]
vendor_id = 0x1209
product_id = 0xFFB0
idle_report_period = "101 ms"
out_interval = "1 ms"
[firmware]
update_rate_hz = 999.0
constant_force_filter = "none"
fade_in = "2 s"
damping_command_s_per_m = 37059
[maps]
roughness = "lab-roughness"
[servo_rate_hz]
min = 900
max = 1000
[calibration]
status = "uncalibrated"
method = "none yet"
source = "USB HID PID class definition 1.0"
)toml");
}

}  // namespace

// Readings worked by hand: commands 0, 1000, 2000, 3000 -> 0.1, 1.0, 2.1, 2.9 N. About the means
// 1500 and 1.525: Sxx = 5e6, Sxy = 4750, so gain 0.00095 N/unit and offset 1.525 - 1.425 = 0.1 N;
// fitted 0.1, 1.05, 2.0, 2.95; residuals 0, -0.05, 0.1, -0.05 (ss 0.015).
TEST(DeviceFit, HandWorkedLine) {
  const auto f = fit_device(parse_device_readings_csv("command,force_N\n0,0.1\n1000,1.0\n2000,2.1\n3000,2.9\n", "g.csv"));
  ASSERT_EQ(f.axes.size(), 1u);
  const auto& a = f.axes[0];
  EXPECT_EQ(a.axis, 0);
  EXPECT_EQ(a.readings, 4);
  EXPECT_EQ(a.command_levels, 4);
  EXPECT_NEAR(a.gain_N_per_unit, 0.00095, 1e-12);
  EXPECT_NEAR(a.offset_N, 0.1, 1e-12);
  EXPECT_NEAR(a.regression.ss_residual, 0.015, 1e-12);
  EXPECT_NEAR(a.gain_se, std::sqrt(0.015 / 2 / 5e6), 1e-12);
  EXPECT_NEAR(a.offset_se, std::sqrt(0.015 / 2 * (0.25 + 1500.0 * 1500 / 5e6)), 1e-12);
  EXPECT_NEAR(a.max_abs_residual_N, 0.1, 1e-12);
  EXPECT_NEAR(a.full_scale_N, 2.95, 1e-12);
  EXPECT_NEAR(a.max_residual_percent, 100 * 0.1 / 2.95, 1e-9);
}

// Synthetic readings with a known gain per axis, an offset, 2 % saturation and noise: the gain is
// recovered within 2 % (the saturation bends the line by about that), and the saturation shows as
// a residual of some tenths of a percent of full scale.
TEST(DeviceFit, RecoversGainsPerAxis) {
  synthetic::GaugeOptions o;
  const auto f = fit_device(synthetic::simulate_gauge(o));
  ASSERT_EQ(f.axes.size(), 2u);
  EXPECT_EQ(f.axes[0].axis, 'x');
  EXPECT_EQ(f.axes[1].axis, 'y');
  EXPECT_NEAR(f.axes[0].gain_N_per_unit, o.gain_x, 0.02 * o.gain_x);
  EXPECT_NEAR(f.axes[1].gain_N_per_unit, o.gain_y, 0.02 * o.gain_y);
  for (const auto& a : f.axes) {
    EXPECT_EQ(a.readings, 22);
    EXPECT_EQ(a.command_levels, 11);
    EXPECT_GT(a.regression.r_squared, 0.999);
    EXPECT_GT(a.max_residual_percent, 0.1);
    EXPECT_LT(a.max_residual_percent, 3.0);
  }
}

// A lowered max_continuous is written to four significant digits and never above the reach:
// 32767 units at 8.3527/32767 N each reach 8.3527 N, which "%.4g" would round up to 8.353.
TEST(DeviceFit, ALoweredMaximumIsTruncatedNotRoundedUp) {
  for (const auto& [reach, written] : {std::pair{8.3527, "8.352 N"}, std::pair{8.3521, "8.352 N"},
                                       std::pair{9.99996, "9.999 N"}, std::pair{0.123456, "0.1234 N"}}) {
    auto f = fit_device(synthetic::simulate_gauge({}));
    for (auto& a : f.axes) a.gain_N_per_unit = reach / 32767;
    const auto doc = toml::parse(device_file_text(f, openffboard_base(), {"", "base.toml", "2026-11-21"}));
    EXPECT_EQ(doc["force"]["max_continuous"].value_or(std::string()), written) << "reach " << reach << " N";
  }
}

TEST(DeviceFit, DeviceFileKeepsTheBaseAndStoresTheGain) {
  const auto f = fit_device(synthetic::simulate_gauge({}));
  const auto text = device_file_text(f, openffboard_base(), {"", "calibration/devices/openffboard-2axis.toml", "2026-11-21"});
  const auto doc = toml::parse(text);
  EXPECT_EQ(doc["schema"].value_or(std::string()), "sandpaper-device/1");
  EXPECT_EQ(doc["name"].value_or(std::string()), "openffboard-2axis");
  EXPECT_EQ(doc["description"].value_or(std::string()).find("uncalibrated"), std::string::npos);
  EXPECT_NEAR(doc["force"]["x"]["newtons_per_command_unit"].value_or(0.0), f.axes[0].gain_N_per_unit, 1e-8 * f.axes[0].gain_N_per_unit);
  EXPECT_NEAR(doc["force"]["y"]["newtons_per_command_unit"].value_or(0.0), f.axes[1].gain_N_per_unit, 1e-8 * f.axes[1].gain_N_per_unit);
  EXPECT_EQ(doc["force"]["command_max"].value_or(0), 32767);
  // Gauge readings measure how hard, not which way: the base's sense stays.
  EXPECT_EQ(doc["force"]["x"]["command_sense"].value_or(0), -1);
  EXPECT_EQ(doc["force"]["y"]["command_sense"].value_or(0), -1);
  EXPECT_EQ(doc["usb"]["idle_report_period"].value_or(std::string()), "101 ms");
  EXPECT_EQ(doc["usb"]["out_interval"].value_or(std::string()), "1 ms");
  // The firmware's chain is in command units: a gauge fit keeps it, and the map the base names.
  EXPECT_EQ(doc["firmware"]["update_rate_hz"].value_or(0.0), 999.0);
  EXPECT_EQ(doc["firmware"]["damping_command_s_per_m"].value_or(0), 37059);
  EXPECT_EQ(doc["firmware"]["fade_in"].value_or(std::string()), "2 s");
  EXPECT_EQ(doc["maps"]["roughness"].value_or(std::string()), "lab-roughness");
  // 32767 x 0.00026 N is about 8.5 N < the base's assumed 10 N: max_continuous comes down to it.
  const auto max = doc["force"]["max_continuous"].value_or(std::string());
  // Four significant digits, never above what the weaker axis reaches: truncated, not rounded.
  const double reach = std::min(f.axes[0].gain_N_per_unit, f.axes[1].gain_N_per_unit) * 32767;
  EXPECT_LE(std::stod(max), reach) << max;
  EXPECT_GT(std::stod(max), reach - 0.001) << max << " for a reach of " << reach;
  EXPECT_EQ(doc["workspace"]["shape"].value_or(std::string()), "rectangle");
  EXPECT_EQ(doc["workspace"]["width"].value_or(std::string()), "100 mm");
  EXPECT_EQ(doc["servo_rate_hz"]["min"].value_or(0), 900);
  EXPECT_EQ(doc["position"]["resolution"].value_or(std::string()), "0.01 mm");
  EXPECT_EQ(doc["calibration"]["status"].value_or(std::string()), "calibrated");
  EXPECT_EQ(doc["calibration"]["date"].value_or(std::string()), "2026-11-21");
  EXPECT_NE(doc["calibration"]["method"].value_or(std::string()).find("offset"), std::string::npos);
  EXPECT_NE(doc["calibration"]["source"].value_or(std::string()).find(f.path), std::string::npos);
  EXPECT_TRUE(doc["calibration"]["residual_max"].is_string());
}

// As MapFile.APathThatIsNotUtf8StillGivesAMapThatLoads, for a device file (F26).
TEST(DeviceFit, APathThatIsNotUtf8StillGivesADeviceFileThatLoads) {
  auto readings = synthetic::simulate_gauge({});
  readings.path = "gauge-\xe9t\xe9.csv";
  const auto f = fit_device(readings);
  const auto doc = toml::parse(device_file_text(f, openffboard_base(), {"", "base-\xff.toml", ""}));
  EXPECT_NE(doc["calibration"]["source"].value_or(std::string()).find("gauge-\xef\xbf\xbdt\xef\xbf\xbd.csv"),
            std::string::npos);
}

// One fit without an axis column serves both axes; with an axis column both must be measured.
TEST(DeviceFit, AxesTheFileNeeds) {
  const auto both = fit_device(parse_device_readings_csv("command,force_N\n0,0\n5000,4.3\n10000,8.4\n", "g.csv"));
  const auto doc = toml::parse(device_file_text(both, openffboard_base(), {}));
  EXPECT_EQ(doc["force"]["x"]["newtons_per_command_unit"].value_or(0.0), doc["force"]["y"]["newtons_per_command_unit"].value_or(-1.0));
  const auto x_only =
      fit_device(parse_device_readings_csv("command,force_N,axis\n0,0,x\n5000,4.3,x\n10000,8.4,x\n", "g.csv"));
  try {
    (void)device_file_text(x_only, openffboard_base(), {});
    FAIL();
  } catch (const FitError& e) {
    EXPECT_NE(e.message.find("no rows for axis y"), std::string::npos) << e.what();
  }
}

// A wheel's file keeps its [wheel] table and its one axis: readings of x alone make it.
TEST(DeviceFit, AWheelIsFittedOnItsOneAxis) {
  const auto base = toml::parse_file(std::string(SANDPAPER_SOURCE_DIR) + "/calibration/devices/openffboard-wheel.toml");
  const auto x_only =
      fit_device(parse_device_readings_csv("command,force_N,axis\n0,0,x\n5000,1.6,x\n10000,3.1,x\n", "rim.csv"));
  const std::string text = device_file_text(x_only, base, {"", "openffboard-wheel.toml", ""});
  const auto doc = toml::parse(text);
  EXPECT_FALSE(doc["force"]["y"].is_table()) << text;
  EXPECT_NEAR(doc["force"]["x"]["newtons_per_command_unit"].value_or(0.0), 3.1 / 10000, 2e-5);
  EXPECT_EQ(doc["wheel"]["rim_radius"].value_or(std::string()), "150 mm");
  EXPECT_EQ(doc["wheel"]["rotation_range"].value_or(std::string()), "900 deg");
  // And the written file loads as a wheel.
  const auto d = parse_device_text(text, "fitted-wheel.toml");
  EXPECT_TRUE(d.wheel());
}
