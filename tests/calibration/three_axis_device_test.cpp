// Three-axis device files (issue 74): [force.z] and a box or sphere [workspace] make a 3-DOF device;
// the shipped ones hold their sources' figures; a 3-D workspace that does not add up is refused with
// a message that names what is wrong; a two-axis file reads as before.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/calibration/device_fit.hpp"
#include "sandpaper/calibration/fit_error.hpp"
#include "synthetic.hpp"

using namespace sandpaper::calibration;

namespace {

const std::string kDevices = std::string(SANDPAPER_SOURCE_DIR) + "/calibration/devices/";

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << "fixture text not found: " << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

// The error parsing `text` gives, or "" when it parses.
std::string error_of(const std::string& text) {
  try {
    parse_device_text(text, "test.toml");
  } catch (const CalibrationError& e) {
    return e.what();
  }
  return {};
}

// One inch and one pound-force, by definition (NIST SP 811: 25.4 mm; 4.4482216152605 N).
constexpr double kInch_m = 0.0254, kPoundForce_N = 4.4482216152605;

TEST(ThreeAxisDevice, TheShippedFilesHoldTheirSourcesFigures) {
  const auto sim3d = load_device_file(kDevices + "sim3d.toml");
  EXPECT_TRUE(sim3d.three_axis());
  EXPECT_EQ(sim3d.status, CalibrationStatus::Definition);
  EXPECT_DOUBLE_EQ(sim3d.max_force_N, 10.0);
  EXPECT_TRUE(sim3d.workspace_circle);  // a sphere of 9 in, as sim's circle
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(sim3d.workspace_size_m[a], 9 * kInch_m, 1e-12);
  EXPECT_NEAR(sim3d.workspace_radius_m, 4.5 * kInch_m, 1e-12);
  EXPECT_DOUBLE_EQ(sim3d.axis_scale(2).newtons_per_command_unit, 1.0);

  // Novint's sheet: a 4 in cube, more than 2 lb of force, 1 kHz.
  const auto falcon = load_device_file(kDevices + "novint-falcon.toml");
  EXPECT_TRUE(falcon.three_axis());
  EXPECT_FALSE(falcon.calibrated());
  EXPECT_FALSE(falcon.workspace_circle);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(falcon.workspace_size_m[a], 4 * kInch_m, 1e-12);
  EXPECT_NEAR(falcon.max_force_N, 2 * kPoundForce_N, 1e-9);
  EXPECT_EQ(falcon.min_rate_hz, 1000);
  EXPECT_EQ(falcon.max_rate_hz, 1000);
  EXPECT_NE(falcon.calibration_source.find("Novint"), std::string::npos);

  // Haply's specifications: 460 x 510 x 230 mm, 4 N over 80 % of the workspace, up to 4000 Hz.
  const auto haply = load_device_file(kDevices + "haply-inverse3.toml");
  EXPECT_TRUE(haply.three_axis());
  EXPECT_FALSE(haply.calibrated());
  EXPECT_NEAR(haply.workspace_size_m[0], 0.460, 1e-12);
  EXPECT_NEAR(haply.workspace_size_m[1], 0.510, 1e-12);
  EXPECT_NEAR(haply.workspace_size_m[2], 0.230, 1e-12);
  EXPECT_NEAR(haply.workspace_radius_m, 0.115, 1e-12);
  EXPECT_DOUBLE_EQ(haply.max_force_N, 4.0);
  EXPECT_EQ(haply.max_rate_hz, 4000);
  EXPECT_NEAR(haply.position_resolution_m, 1e-5, 1e-15);
  EXPECT_NE(haply.calibration_source.find("Haply"), std::string::npos);
}

TEST(ThreeAxisDevice, ATwoAxisFileReadsAsBefore) {
  for (const char* name : {"sim", "sandpaper-1995", "openffboard-2axis"}) {
    const auto d = load_device_file(kDevices + name + ".toml");
    EXPECT_EQ(d.axes, 2) << name;
    EXPECT_EQ(d.workspace_size_m[2], 0.0) << name << ": a flat workspace has no depth";
  }
  EXPECT_EQ(load_device_file(kDevices + "openffboard-wheel.toml").axes, 1);
}

TEST(ThreeAxisDevice, AThreeDWorkspaceThatDoesNotAddUpIsRefusedWithWhatIsWrong) {
  const std::string falcon = read(kDevices + "novint-falcon.toml");
  const std::string sim3d = read(kDevices + "sim3d.toml");
  const std::string sim = read(kDevices + "sim.toml");
  ASSERT_EQ(error_of(falcon), "");
  ASSERT_EQ(error_of(sim3d), "");

  // A box without its depth.
  auto err = error_of(replace(falcon, "depth = \"4 in\"\n", ""));
  EXPECT_NE(err.find("a box workspace needs `width`, `height` and `depth` (along x, y and z)"), std::string::npos) << err;
  // A sphere without its diameter.
  err = error_of(replace(sim3d, "diameter = \"9 in\"\n", ""));
  EXPECT_NE(err.find("a spherical workspace needs `diameter`"), std::string::npos) << err;
  // Three force axes on a flat workspace.
  err = error_of(replace(sim3d, "shape = \"sphere\"", "shape = \"circle\""));
  EXPECT_NE(err.find("a three-axis device ([force.z]) moves in a volume: its workspace is a box or a sphere, not a circle"),
            std::string::npos)
      << err;
  // A volume for a two-axis device.
  err = error_of(replace(sim, "shape = \"circle\"", "shape = \"sphere\""));
  EXPECT_NE(err.find("a sphere workspace is for a three-axis device, and this file gives no [force.z]"), std::string::npos) << err;
  // Depth on a flat or round workspace.
  err = error_of(replace(sim, "diameter = \"9 in\"", "diameter = \"9 in\"\ndepth = \"9 in\""));
  EXPECT_NE(err.find("`depth` is for a box workspace (width x height x depth); a circle has none"), std::string::npos) << err;
  // A z without a y.
  err = error_of(replace(sim3d, "[force.y]\nnewtons_per_command_unit = 1.0\n", ""));
  EXPECT_NE(err.find("a three-axis device needs [force.y] as well as [force.x] and [force.z]"), std::string::npos) << err;
  // The schema's own refusals, before the file is read: a depth that is not a length, a shape it does not know.
  err = error_of(replace(falcon, "depth = \"4 in\"", "depth = \"4 N\""));
  EXPECT_NE(err.find("\"4 N\" is a force, expected a length"), std::string::npos) << err;
  err = error_of(replace(falcon, "shape = \"box\"", "shape = \"cube\""));
  EXPECT_NE(err.find("shape"), std::string::npos) << err;
  // Every problem is at its line: the file is named with line and column.
  EXPECT_NE(error_of(replace(falcon, "depth = \"4 in\"\n", "")).find("test.toml:"), std::string::npos);
}

// `sandpaper calibrate device` on a three-axis base: one fit for all axes is written to [force.z]
// too; readings per axis (x and y only) are refused with the reason.
TEST(ThreeAxisDevice, ACalibratedThreeAxisFileKeepsItsZ) {
  const std::string base_path = kDevices + "novint-falcon.toml";
  const auto base = toml::parse_file(base_path);
  auto readings = synthetic::simulate_gauge({});
  EXPECT_THROW(device_file_text(fit_device(readings), base, {"", base_path, ""}), FitError);
  readings.has_axis = false;
  for (auto& r : readings.readings) r.axis = 0;
  const auto fit = fit_device(readings);
  ASSERT_EQ(fit.axes.size(), 1u);
  const auto d = parse_device_text(device_file_text(fit, base, {"", base_path, ""}), "written.toml");
  EXPECT_TRUE(d.three_axis());
  EXPECT_TRUE(d.calibrated());
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(d.axis_scale(a).newtons_per_command_unit, fit.axes[0].gain_N_per_unit, 1e-8 * fit.axes[0].gain_N_per_unit);
  EXPECT_NEAR(d.workspace_size_m[2], 4 * kInch_m, 1e-12);
}

}  // namespace
