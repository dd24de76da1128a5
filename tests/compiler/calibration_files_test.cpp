// The calibration data as shipped: every file loads and validates against its schema in
// schema/files/, the comparison maps hold the thesis' numbers, and broken files are refused with
// every problem at its file:line:col.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/schema/file_schema.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {

namespace fs = std::filesystem;
const fs::path kShipped = fs::path(SANDPAPER_SOURCE_DIR) / "calibration";

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write(const fs::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
}

// A copy of the shipped calibration directory to break one file of.
fs::path copy_of_shipped(const std::string& tag) {
  fs::path dir = fs::path(test::temp_dir(tag)) / "calibration";
  fs::copy(kShipped, dir, fs::copy_options::recursive);
  return dir;
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << "fixture text not found: " << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

// The load error for a directory; empty if it loads.
std::string load_error(const fs::path& dir) {
  try {
    calibration::CalibrationSet::load(dir);
  } catch (const calibration::CalibrationError& e) {
    return e.what();
  }
  return {};
}

TEST(CalibrationFiles, EveryShippedFileNamesItsSchemaAndLoads) {
  auto cal = calibration::CalibrationSet::load(kShipped);
  EXPECT_GE(cal.maps().size(), 3u);
  EXPECT_EQ(cal.devices().size(), 7u);  // sim, sim3d, sandpaper-1995, two OpenFFBoards, the Falcon and the Inverse3
  ASSERT_EQ(cal.profiles().size(), 1u);
  EXPECT_EQ(cal.find_device("uncalibrated-evdev"), &cal.profiles()[0]) << "a profile is found by name, apart from the devices";
  // Each file's `schema` key names a shipped schema whose const it satisfies.
  std::map<std::string, std::string> folder_schema = {{"maps", "sandpaper-map/1"},
                                                      {"devices", "sandpaper-device/1"},
                                                      {"profiles", "sandpaper-device/1"},
                                                      {"levels", "sandpaper-levels/1"}};
  for (const auto& [folder, tag] : folder_schema)
    for (const auto& e : fs::directory_iterator(kShipped / folder)) {
      if (e.path().extension() != ".toml") continue;
      EXPECT_NE(read(e.path()).find("schema = \"" + tag + "\""), std::string::npos) << e.path();
    }
}

TEST(CalibrationFiles, SchemasAreJsonSchemaDocuments) {
  auto names = schema::file_schema_names();
  for (const char* want : {"map", "device", "levels", "force-jnd"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  for (const auto& n : names) {
    auto j = nlohmann::json::parse(schema::file_schema_text(n));
    EXPECT_EQ(j.value("$schema", ""), "http://json-schema.org/draft-07/schema#") << n;
    EXPECT_EQ(j.value("type", ""), "object") << n;
    // The binary carries the same text as the file editors use.
    EXPECT_EQ(std::string(schema::file_schema_text(n)),
              read(fs::path(SANDPAPER_SOURCE_DIR) / "schema/files" / (n + ".schema.json")))
        << n;
  }
}

TEST(CalibrationFiles, Figure20ShowsPeriodAddsNothing) {
  auto cal = calibration::CalibrationSet::load(kShipped);
  const auto* m = cal.find_map("minsky1995-fig20");
  ASSERT_NE(m, nullptr);
  EXPECT_FALSE(m->for_compile);
  const auto* amp = m->predictor("force");
  const auto* per = m->predictor("period");
  ASSERT_TRUE(amp && per);
  EXPECT_DOUBLE_EQ(amp->coefficient, 0.514422);
  EXPECT_DOUBLE_EQ(*amp->se, 0.0489);
  EXPECT_DOUBLE_EQ(per->coefficient, -0.056435);
  // Not significant: |t| < 2 and the stated p, and the t-ratio is coefficient / s.e.
  EXPECT_LT(std::abs(*per->t), 2.0);
  EXPECT_NEAR(*per->t, per->coefficient / *per->se, 0.01);
  EXPECT_NEAR(*amp->t, amp->coefficient / *amp->se, 0.05);
  EXPECT_GT(*per->p, 0.05);
  EXPECT_EQ(*m->degrees_of_freedom, 28);
  EXPECT_FALSE(m->intercept.has_value());  // a regression through the origin
  ASSERT_TRUE(m->period.has_value());
  EXPECT_NEAR(m->period->min, 0.7e-3, 1e-12);
}

TEST(CalibrationFiles, Lederman1972IsAFingertipComparisonNeverCompiledThrough) {
  auto cal = calibration::CalibrationSet::load(kShipped);
  const auto* m = cal.find_map("lederman1972");
  ASSERT_NE(m, nullptr);
  EXPECT_FALSE(m->for_compile);
  EXPECT_EQ(m->predictors.at(0).coefficient, 0.25);
  EXPECT_NE(m->effector.find("fingertip"), std::string::npos);
  EXPECT_NE(cal.compile_map("roughness")->id, "lederman1972");
  ASSERT_TRUE(m->force.has_value());
  EXPECT_NEAR(m->force->max / m->force->min, 25.0, 1e-9);  // 1 to 25 oz (thesis 5.3.1)
}

TEST(CalibrationFiles, Figure19StatisticsAreConsistent) {
  const auto& m = calibration::CalibrationSet::load(kShipped).roughness_map();
  // t = coefficient / s.e. as printed (28.1 and -11.0), and F = t^2 for one predictor.
  const auto& f = m.predictors.at(0);
  EXPECT_NEAR(f.coefficient / *f.se, *f.t, 0.05);
  EXPECT_NEAR(*m.intercept / *m.intercept_se, -11.0, 0.05);
  EXPECT_NEAR(*f.t * *f.t, *m.f_ratio, 0.01 * *m.f_ratio);
  // Adjusted R^2 from R^2, n = 30 stimuli and one predictor.
  EXPECT_NEAR(1 - (1 - *m.r_squared) * (30 - 1) / (30 - 2), *m.r_squared_adjusted, 0.001);
}

TEST(CalibrationFiles, DeviceFilesInSIUnits) {
  auto cal = calibration::CalibrationSet::load(kShipped);
  const auto* thesis = cal.find_device("sandpaper-1995");
  ASSERT_NE(thesis, nullptr);
  EXPECT_NEAR(thesis->workspace_radius_m, 0.1143, 1e-9);  // 9 inch circle
  EXPECT_NEAR(thesis->position_resolution_m, 0.2286 / 4096, 1e-7);  // 12 bit
  EXPECT_EQ(thesis->command_max, 2048);
  EXPECT_EQ(thesis->resolution_bits, 12);
  EXPECT_EQ(thesis->min_rate_hz, 900);
  EXPECT_NEAR(thesis->axis_scale(0).newtons(1), 4.814e-3, 1e-6);  // "about 4.8 mN" per joystick unit
  EXPECT_TRUE(thesis->calibrated());
  const auto* usb = cal.find_device("openffboard-2axis");
  ASSERT_NE(usb, nullptr);
  EXPECT_FALSE(usb->calibrated());
  EXPECT_FALSE(usb->workspace_circle);
  EXPECT_EQ(usb->file, "calibration/devices/openffboard-2axis.toml");
  // [firmware]: the OpenFFBoard's chain (usb-lab/firmware/README.md): 1001 us updates, a 2 s fade,
  // its damper 9000 deg/m x 30 x 28 / 204 command units per m/s, at 10 N over 32767 units.
  ASSERT_TRUE(usb->has_firmware());
  EXPECT_NEAR(usb->firmware.update_rate_hz, 1e6 / 1001, 0.1);
  EXPECT_DOUBLE_EQ(usb->firmware.fade_in_s, 2.0);
  EXPECT_NEAR(usb->firmware_damping_N(0, 0.1), 9000.0 * 30 * 28 / 204 * 0.1 * 10 / 32767, 1e-3);
  EXPECT_NEAR(usb->firmware_damping_N(1, -0.1), usb->firmware_damping_N(1, 0.1), 1e-12);
  EXPECT_FALSE(cal.find_device("sandpaper-1995")->has_firmware());
  EXPECT_EQ(usb->axes, 2);
  EXPECT_EQ(usb->wheel_deg_per_mm(), 0.0);
  // The wheel: one axis along a 150 mm rim over 900 degrees (openffboard-wheel.toml's assumptions):
  // 1 mm of rim is 180 / (150 pi) = 0.38197 degrees, the rim's arc 2356.19 mm.
  const auto* wheel = cal.find_device("openffboard-wheel");
  ASSERT_NE(wheel, nullptr);
  EXPECT_TRUE(wheel->wheel());
  EXPECT_EQ(wheel->axes, 1);
  EXPECT_NEAR(wheel->wheel_rim_radius_m, 0.150, 1e-12);
  EXPECT_NEAR(wheel->wheel_rotation_range_rad, 900 * M_PI / 180, 1e-12);
  EXPECT_NEAR(wheel->wheel_deg_per_mm(), 180 / (150 * M_PI), 1e-9);
  EXPECT_NEAR(wheel->workspace_size_m[0], 0.15 * 5 * M_PI, 1e-4);
  EXPECT_EQ(wheel->usb_vendor_id, usb->usb_vendor_id);  // the same board: told apart by its effects' axes
  EXPECT_EQ(wheel->usb_product_id, usb->usb_product_id);
  EXPECT_DOUBLE_EQ(wheel->axis_scale(1).newtons_per_command_unit, wheel->axis_scale(0).newtons_per_command_unit);
  // Its damper: 1 m/s of rim is 1000 / 150 rad/s = 381.97 deg/s, x 30 x 28 / 204 command units.
  EXPECT_NEAR(wheel->firmware_damping_N(0, 0.1), 180 / (0.15 * M_PI) * 30 * 28 / 204 * 0.1 * 10 / 32767, 1e-4);
  const auto* sim = cal.find_device("sim");
  ASSERT_NE(sim, nullptr);
  EXPECT_FALSE(sim->quantized());
  EXPECT_EQ(sim->quantize_N(0, 0.123456), 0.123456);
}

TEST(AxisScale, TableInterpolatesBothWaysAndMirrorsNegativeCommands) {
  calibration::AxisScale s;
  s.table = {{0, 0}, {100, 0.5}, {200, 1.2}, {400, 2.0}};
  EXPECT_NEAR(s.newtons(50), 0.25, 1e-12);
  EXPECT_NEAR(s.newtons(150), 0.85, 1e-12);
  EXPECT_NEAR(s.newtons(-150), -0.85, 1e-12);
  EXPECT_NEAR(s.newtons(300), 1.6, 1e-12);
  for (double c : {0.0, 10.0, 99.0, 150.0, 399.0, -250.0}) EXPECT_NEAR(s.command(s.newtons(c)), c, 1e-9) << c;
  EXPECT_NEAR(s.step_N(0.85), 0.007, 1e-12);  // slope of the 100-200 segment
  calibration::AxisScale linear;
  linear.newtons_per_command_unit = 0.002;
  EXPECT_NEAR(linear.command(1.0), 500, 1e-9);
  EXPECT_NEAR(linear.step_N(3.0), 0.002, 1e-15);
}

// --- broken files: refused with file:line:col, all problems in one report -------------------

TEST(CalibrationFiles, MissingRequiredKeyIsReportedAtItsTable) {
  auto dir = copy_of_shipped("cal-missing");
  auto f = dir / "devices/sandpaper-1995.toml";
  write(f, replace(read(f), "max_continuous = \"10 N\"", "# max_continuous removed"));
  auto err = load_error(dir);
  EXPECT_NE(err.find("calibration/devices/sandpaper-1995.toml:"), std::string::npos) << err;
  EXPECT_NE(err.find("missing required key `max_continuous`"), std::string::npos) << err;
  EXPECT_NE(err.find("schema/files/device.schema.json"), std::string::npos) << err;
}

TEST(CalibrationFiles, WrongDimensionAndTyposAreReportedWithPositions) {
  auto dir = copy_of_shipped("cal-dimension");
  auto f = dir / "devices/sandpaper-1995.toml";
  std::string text = read(f);
  text = replace(text, "max_continuous = \"10 N\"", "max_continuous = \"10 mm\"");
  text = replace(text, "resolution_bits = 12", "resolution_bitz = 12");
  write(f, text);
  auto err = load_error(dir);
  // Line and column of the offending values, counted in the fixture itself.
  int line = 0, dim_line = 0, typo_line = 0;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) {
    ++line;
    if (l.find("\"10 mm\"") != std::string::npos) dim_line = line;
    if (l.find("resolution_bitz") != std::string::npos) typo_line = line;
  }
  EXPECT_NE(err.find("sandpaper-1995.toml:" + std::to_string(dim_line) + ":18: error: `force.max_continuous`: \"10 mm\" is a length, expected a force"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("sandpaper-1995.toml:" + std::to_string(typo_line) + ":1: error: `force.resolution_bitz`: unknown key"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("expected one of: "), std::string::npos) << err;
}

TEST(CalibrationFiles, ProblemsInSeveralFilesComeInOneReport) {
  auto dir = copy_of_shipped("cal-several");
  auto dev = dir / "devices/openffboard-2axis.toml";
  write(dev, replace(read(dev), "[force.x]\nnewtons_per_command_unit = 0.0003051850947599719   # 10 N / 32767", "[force.x]"));
  auto map = dir / "maps/minsky1995-fig19.toml";
  write(map, replace(read(map), "status = \"measured\"", "status = \"guessed\""));
  auto err = load_error(dir);
  EXPECT_NE(err.find("openffboard-2axis.toml"), std::string::npos) << err;
  EXPECT_NE(err.find("give `newtons_per_command_unit` or a `table`"), std::string::npos) << err;
  EXPECT_NE(err.find("minsky1995-fig19.toml"), std::string::npos) << err;
  EXPECT_NE(err.find("must be one of \"measured\", \"provisional\""), std::string::npos) << err;
}

TEST(CalibrationFiles, ConsistencyRulesBeyondTheSchema) {
  {
    // A second roughness compile map: ambiguous.
    auto dir = copy_of_shipped("cal-two-compile");
    auto f = dir / "maps/minsky1995-fig20.toml";
    write(f, replace(replace(read(f), "use = \"comparison\"", "use = \"compile\""), "[domain]",
                     "[ratio_scale]\npredictor = \"force\"\nreference = \"382 gf\"\n\n[domain]"));
    auto err = load_error(dir);
    EXPECT_NE(err.find("a compile map has exactly one predictor"), std::string::npos) << err;
    EXPECT_NE(err.find("2 maps have percept = \"roughness\" and use = \"compile\""), std::string::npos) << err;
  }
  {
    // A profile named as a device: `--device sim` would mean two files.
    auto dir = copy_of_shipped("cal-profile-name");
    auto f = dir / "profiles/uncalibrated-evdev.toml";
    write(f, replace(read(f), "name = \"uncalibrated-evdev\"", "name = \"sim\""));
    auto err = load_error(dir);
    EXPECT_NE(err.find("`sim` is a profile name that is also a device's"), std::string::npos) << err;
  }
  {
    // Levels on a map that does not exist.
    auto dir = copy_of_shipped("cal-levels");
    auto f = dir / "levels/roughness-levels.toml";
    write(f, replace(read(f), "map = \"minsky1995-fig19\"", "map = \"minsky1995-fig99\""));
    EXPECT_NE(load_error(dir).find("levels refer to map `minsky1995-fig99`"), std::string::npos);
  }
  {
    // A compile map without its ratio scale.
    auto dir = copy_of_shipped("cal-ratio");
    auto f = dir / "maps/minsky1995-fig19.toml";
    std::string text = read(f);
    auto from = text.find("[ratio_scale]");
    auto to = text.find("[domain]");
    text.erase(from, to - from);
    write(f, text);
    EXPECT_NE(load_error(dir).find("needs a [ratio_scale]"), std::string::npos);
  }
  {
    // A misspelt firmware key, and a filter the model does not know.
    auto dir = copy_of_shipped("cal-firmware");
    auto f = dir / "devices/openffboard-2axis.toml";
    write(f, replace(replace(read(f), "fade_in = ", "fadein = "), "constant_force_filter = \"none\"",
                     "constant_force_filter = \"biquad\""));
    const auto err = load_error(dir);
    EXPECT_NE(err.find("`firmware.fadein`: unknown key"), std::string::npos) << err;
    EXPECT_NE(err.find("constant_force_filter"), std::string::npos) << err;
  }
  {
    // A force table that falls.
    auto dir = copy_of_shipped("cal-table");
    auto f = dir / "devices/openffboard-2axis.toml";
    write(f, replace(read(f), "[force.y]\nnewtons_per_command_unit = 0.0003051850947599719   # 10 N / 32767",
                     "[force.y]\ntable = [{command = 0, force = \"0 N\"}, {command = 5000, force = \"6 N\"}, "
                     "{command = 10000, force = \"5 N\"}]"));
    EXPECT_NE(load_error(dir).find("force.y.table must rise"), std::string::npos);
  }
}

TEST(CalibrationFiles, AWheelsFileSaysOneAxisAndItsRim) {
  {
    // A width that is not the rim's arc over the rotation range.
    auto dir = copy_of_shipped("cal-wheel-width");
    auto f = dir / "devices/openffboard-wheel.toml";
    write(f, replace(read(f), "width = \"2356.2 mm\"", "width = \"100 mm\""));
    const auto err = load_error(dir);
    EXPECT_NE(err.find("a wheel's workspace is a rectangle whose width is its rim's arc over the rotation range, 2356.2 mm"),
              std::string::npos)
        << err;
  }
  {
    // A force.y on a wheel; then (the schema's refusals, before the file is read) a rotation range
    // that is not an angle, and a rim without a radius.
    auto dir = copy_of_shipped("cal-wheel-y");
    auto f = dir / "devices/openffboard-wheel.toml";
    const std::string shipped = read(f);
    write(f, replace(shipped, "[wheel]", "[force.y]\nnewtons_per_command_unit = 0.001\n\n[wheel]"));
    auto err = load_error(dir);
    EXPECT_NE(err.find("a wheel ([wheel]) has one force axis"), std::string::npos) << err;
    write(f, replace(shipped, "rotation_range = \"900 deg\"", "rotation_range = \"900 mm\""));
    err = load_error(dir);
    EXPECT_NE(err.find("\"900 mm\" is a length, expected an angle"), std::string::npos) << err;
    write(f, replace(shipped, "rim_radius = \"150 mm\"\n", ""));
    err = load_error(dir);
    EXPECT_NE(err.find("rim_radius"), std::string::npos) << err;
  }
  {
    // A rim radius in metres where millimetres were meant, and a range of eleven turns.
    auto dir = copy_of_shipped("cal-wheel-rim");
    auto f = dir / "devices/openffboard-wheel.toml";
    write(f, replace(replace(read(f), "rim_radius = \"150 mm\"", "rim_radius = \"150 m\""),
                     "rotation_range = \"900 deg\"", "rotation_range = \"3960 deg\""));
    const auto err = load_error(dir);
    EXPECT_NE(err.find("a wheel's rim radius is between 5 mm and 1 m"), std::string::npos) << err;
    EXPECT_NE(err.find("a wheel's rotation range is at most 3600 deg"), std::string::npos) << err;
  }
  {
    // A joystick without its y scale is not taken for a wheel.
    auto dir = copy_of_shipped("cal-no-y");
    auto f = dir / "devices/openffboard-2axis.toml";
    write(f, replace(read(f), "[force.y]\nnewtons_per_command_unit = 0.0003051850947599719   # 10 N / 32767\ncommand_sense = -1\n", ""));
    const auto err = load_error(dir);
    EXPECT_NE(err.find("a two-axis device needs [force.y]"), std::string::npos) << err;
  }
}

TEST(CalibrationFiles, UnchangedCopyLoads) {
  // The fixtures above fail because of their edits, not because of the copying.
  EXPECT_EQ(load_error(copy_of_shipped("cal-unchanged")), "");
}

// W0302 names the periods the compile map was measured on, read from the map, not the shipped
// map's 0.7-10 mm: a lab's map measured on 1-5 mm warns at 7 mm and says 1-5 mm.
TEST(CalibrationFiles, APeriodOutsideTheMapsDomainIsNamedWithThatDomain) {
  auto dir = copy_of_shipped("cal-domain");
  auto f = dir / "maps/minsky1995-fig19.toml";
  write(f, replace(read(f), "period = [\"0.7 mm\", \"10 mm\"]", "period = [\"1 mm\", \"5 mm\"]"));
  compiler::CompileOptions co;
  co.calibration_dir = dir;
  const compiler::Compiler c(co);
  const auto r = c.compile_text("grating period 7 mm; roughness 0.5");
  ASSERT_TRUE(r.ok());
  const compiler::Diagnostic* w = nullptr;
  for (const auto& d : r.diagnostics.all())
    if (d.code == "W0302") w = &d;
  ASSERT_NE(w, nullptr);
  EXPECT_NE(w->message.find("grating period 7 mm is outside the periods the minsky1995-fig19 map was measured on (1-5 mm)"),
            std::string::npos)
      << w->message;
  EXPECT_EQ(w->suggestion, "periods from 1 mm to 5 mm keep the prediction inside the data");
  // Inside the lab's domain there is no W0302.
  const auto inside = c.compile_text("grating period 3 mm; roughness 0.5");
  for (const auto& d : inside.diagnostics.all()) EXPECT_NE(d.code, "W0302") << d.message;
}

}  // namespace
}  // namespace sandpaper
