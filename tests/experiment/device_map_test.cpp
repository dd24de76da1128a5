// A device's own roughness map (docs/EXPERIMENTS.md, "Installing the map"): a use = "device" map
// compiles for the device it names and for no other; a device file may name its map; mistakes in
// either are refused at load with the file named.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sandpaper/compiler/compiler.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {

namespace fs = std::filesystem;

const char* kSimMap = R"(schema = "sandpaper-map/1"
id = "sim-roughness"
percept = "roughness"
status = "measured"
use = "device"
law = "log-linear"
description = "test map"
[[predictor]]
name = "force"
quantity = "maximum lateral force"
unit = "N"
coefficient = 0.5
[intercept]
value = 1.0
[ratio_scale]
predictor = "force"
reference = "2 N"
[domain]
force = ["0.1 N", "4 N"]
device = "sim"
[source]
citation = "test"
where = "test"
)";

fs::path calibration_with(const std::string& tag, const std::string& map_text, const std::string& map_name = "sim-roughness.toml") {
  const fs::path dir = fs::path(test::temp_dir(tag)) / "calibration";
  fs::copy(fs::path(SANDPAPER_SOURCE_DIR) / "calibration", dir, fs::copy_options::recursive);
  std::ofstream(dir / "maps" / map_name) << map_text;
  return dir;
}

compiler::Compiler compiler_for(const fs::path& cal, const std::string& device) {
  compiler::CompileOptions o;
  o.device = device;
  o.calibration_dir = cal;
  return compiler::Compiler(o);
}

TEST(DeviceMap, CompilesForItsDeviceOnly) {
  const auto cal = calibration_with("devmap", kSimMap);
  const auto sim = compiler_for(cal, "sim");
  EXPECT_EQ(sim.calibration().roughness_map().id, "sim-roughness");
  const auto r = sim.compile_text("grating period 2.5 mm; roughness 0.6");
  ASSERT_TRUE(r.ok());
  // F = 2 N x 0.6^(1/0.5) = 0.72 N.
  EXPECT_NEAR(r.program->max_lateral_force_N, 0.72, 1e-9);
  const auto other = compiler_for(cal, "openffboard-2axis");
  EXPECT_EQ(other.calibration().roughness_map().id, "minsky1995-fig19");
  EXPECT_EQ(sim.calibration().default_compile_map("roughness")->id, "minsky1995-fig19");
}

TEST(DeviceMap, DeviceFileNamesItsMap) {
  std::string named = kSimMap;
  named.replace(named.find("id = \"sim-roughness\""), 20, "id = \"lab-map\"      ");
  named.replace(named.find("device = \"sim\""), 14, "device = \"openffboard-2axis\"");
  const auto cal = calibration_with("devmap-named", named, "lab-map.toml");
  std::ofstream(cal / "devices" / "sim.toml", std::ios::app) << "\n[maps]\nroughness = \"minsky1995-fig19\"\n";
  EXPECT_EQ(compiler_for(cal, "sim").calibration().roughness_map().id, "minsky1995-fig19");
  EXPECT_EQ(compiler_for(cal, "openffboard-2axis").calibration().roughness_map().id, "lab-map");
}

std::string load_error(const fs::path& cal) {
  try {
    calibration::CalibrationSet::load(cal);
  } catch (const calibration::CalibrationError& e) {
    return e.what();
  }
  return "";
}

TEST(DeviceMap, MistakesAreRefused) {
  std::string unknown = kSimMap;
  unknown.replace(unknown.find("device = \"sim\""), 14, "device = \"nosuch\"");
  EXPECT_NE(load_error(calibration_with("devmap-unknown", unknown)).find("for device `nosuch`, which calibration/devices/ lacks"),
            std::string::npos);

  const auto two = calibration_with("devmap-two", kSimMap);
  std::string second = kSimMap;
  second.replace(second.find("id = \"sim-roughness\""), 20, "id = \"sim-roughness2\"");
  std::ofstream(two / "maps" / "sim-roughness2.toml") << second;
  EXPECT_NE(load_error(two).find("device `sim` already has a roughness map"), std::string::npos) << load_error(two);

  const auto named = calibration_with("devmap-missing", kSimMap);
  std::ofstream(named / "devices" / "sim.toml", std::ios::app) << "\n[maps]\nroughness = \"nosuch-map\"\n";
  EXPECT_NE(load_error(named).find("[maps] roughness names map `nosuch-map`"), std::string::npos) << load_error(named);

  std::string no_device = kSimMap;
  no_device.erase(no_device.find("device = \"sim\"\n"), 15);
  EXPECT_NE(load_error(calibration_with("devmap-nodev", no_device)).find("names its device in [domain] device"),
            std::string::npos);
}

}  // namespace
}  // namespace sandpaper
