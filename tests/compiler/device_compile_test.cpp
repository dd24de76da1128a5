// Compiling is device-dependent (issue 4): the same material gives the same newtons at the hand on
// every device that can reach it, in each device's own command units; a percept a device cannot
// reach is reported with the best value it can reach; every number names the map and device file
// it came from.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include <gtest/gtest.h>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {

namespace fs = std::filesystem;

compiler::Compiler for_device(const std::string& device, const fs::path& calibration_dir = {}) {
  compiler::CompileOptions o;
  o.device = device;
  o.calibration_dir = calibration_dir;
  return compiler::Compiler(o);
}

bool has_code(const compiler::CompileResult& r, const std::string& code) {
  for (const auto& d : r.diagnostics.all())
    if (d.code == code) return true;
  return false;
}

const compiler::Diagnostic* find_code(const compiler::CompileResult& r, const std::string& code) {
  for (const auto& d : r.diagnostics.all())
    if (d.code == code) return &d;
  return nullptr;
}

// The force the device actually produces for the program's maximum lateral force on axis x: the
// command rounded to the device's resolution, turned back into newtons with the device file's scale.
double played_newtons(const compiler::Compiler& c, const schema::PatchProgram& p) {
  const auto& d = c.device();
  return d.quantize_N(0, p.max_lateral_force_N);
}

TEST(DeviceCompile, SameNewtonsDifferentCommandUnitsOnTheThesisAndUsbJoysticks) {
  const auto thesis = for_device("sandpaper-1995");
  const auto usb = for_device("openffboard-2axis");
  for (const char* material : {"corduroy", "like corduroy; roughness 0.2", "grating period 5 mm; roughness 0.9",
                               "silk-satin", "denim-twill", "gravel"}) {
    auto a = thesis.compile_text(material);
    auto b = usb.compile_text(material);
    ASSERT_TRUE(a.ok() && b.ok()) << material;
    const auto& pa = *a.program;
    const auto& pb = *b.program;
    ASSERT_GT(pa.max_lateral_force_N, 0) << material;
    // Newtons at the hand: the device-rounded command, back through each device file, within 1 %.
    double na = played_newtons(thesis, pa), nb = played_newtons(usb, pb);
    EXPECT_NEAR(na / nb, 1.0, 0.01) << material << ": " << na << " N vs " << nb << " N";
    EXPECT_NEAR(na / pa.max_lateral_force_N, 1.0, 0.01) << material;
    // Command units: ju on the thesis joystick, PID magnitude on the USB joystick, in the ratio of
    // their scales (10/32767 / 0.004814 = 0.0634).
    double ua = pa.max_lateral_force_N / pa.command.newtons_per_command_unit[0];
    double ub = pb.max_lateral_force_N / pb.command.newtons_per_command_unit[0];
    EXPECT_NE(std::round(ua), std::round(ub)) << material;
    EXPECT_NEAR(ub / ua, 0.00481417274 / (10.0 / 32767), 1e-9) << material;
    EXPECT_EQ(pa.command.command_unit, "ju");
    EXPECT_EQ(pb.command.command_unit, "PID magnitude");
    EXPECT_EQ(pa.command.command_max, 2048);
    EXPECT_EQ(pb.command.command_max, 32767);
  }
}

// `library check` compiles every entry once per device with compilers that share one read of the
// library: each must still compile for its own device, exactly as a compiler with its own copy does.
TEST(DeviceCompile, CompilersSharingOneLibraryCompileForTheirOwnDevices) {
  const auto library = std::make_shared<const compiler::Library>(compiler::default_library_dir());
  compiler::CompileOptions o;
  o.device = "sandpaper-1995";
  const compiler::Compiler thesis(o, library);
  o.device = "openffboard-2axis";
  const compiler::Compiler usb(o, library);
  EXPECT_EQ(&thesis.library(), library.get());
  EXPECT_EQ(&usb.library(), library.get());
  for (const char* material : {"corduroy", "like corduroy; roughness 0.2", "gravel"}) {
    const auto a = thesis.compile_text(material), b = usb.compile_text(material);
    const auto own_a = for_device("sandpaper-1995").compile_text(material);
    const auto own_b = for_device("openffboard-2axis").compile_text(material);
    ASSERT_TRUE(a.ok() && b.ok() && own_a.ok() && own_b.ok()) << material;
    EXPECT_EQ(a.program->command.command_unit, "ju") << material;
    EXPECT_EQ(b.program->command.command_unit, "PID magnitude") << material;
    EXPECT_EQ(a.program->command.newtons_per_command_unit[0], own_a.program->command.newtons_per_command_unit[0]) << material;
    EXPECT_EQ(b.program->command.newtons_per_command_unit[0], own_b.program->command.newtons_per_command_unit[0]) << material;
    EXPECT_EQ(a.program->max_lateral_force_N, own_a.program->max_lateral_force_N) << material;
    EXPECT_EQ(b.program->max_lateral_force_N, own_b.program->max_lateral_force_N) << material;
  }
}

TEST(DeviceCompile, CorduroyOnTheThesisJoystickIs354JoystickUnits) {
  auto r = for_device("sandpaper-1995").compile_text("corduroy");
  ASSERT_TRUE(r.ok());
  const auto& cmd = test::provenance(*r.program, "texture.max_force_command");
  // 1.7052 N / 4.814 mN per ju, rounded as the 12-bit joystick rounds.
  EXPECT_EQ(cmd.value_si, std::round(r.program->max_lateral_force_N / 0.00481417274));
  EXPECT_NE(cmd.stated.find(" ju = "), std::string::npos) << cmd.stated;
  EXPECT_EQ(cmd.source, "calibration/devices/sandpaper-1995.toml");
}

TEST(DeviceCompile, EveryCalibratedNumberNamesItsMapAndDeviceFile) {
  auto r = for_device("sandpaper-1995").compile_text("like corduroy; roughness 0.6");
  ASSERT_TRUE(r.ok());
  const auto& p = *r.program;
  EXPECT_EQ(p.roughness_map_file, "calibration/maps/minsky1995-fig19.toml");
  EXPECT_EQ(p.command.device_file, "calibration/devices/sandpaper-1995.toml");
  for (const char* map_dependent : {"texture.max_lateral_force", "texture.roughness"})
    EXPECT_NE(test::provenance(p, map_dependent).source.find("calibration/maps/minsky1995-fig19.toml"), std::string::npos)
        << map_dependent;
  for (const char* device_dependent : {"device.max_force", "device.command_scale", "texture.max_force_command"})
    EXPECT_EQ(test::provenance(p, device_dependent).source, "calibration/devices/sandpaper-1995.toml") << device_dependent;
}

TEST(DeviceCompile, UnreachableRoughnessIsAnErrorWithTheReachableLimit) {
  auto c = for_device("sandpaper-1995");
  auto r = c.compile_text("like corduroy; extrapolate; roughness 3");
  ASSERT_FALSE(r.ok());
  const auto* d = find_code(r, "E0310");
  ASSERT_NE(d, nullptr);
  // 10 N, the device limit, on the loaded map: (10 N / 3.746 N)^0.759593 = 2.108, shown as 2.1.
  double best = c.calibration().roughness_map().percept_of(c.device().max_force_N);
  std::ostringstream os;
  os << std::floor(best * 100) / 100;  // shown rounded down to three digits: 2.10 prints as 2.1
  EXPECT_NE(d->message.find("reaches 10 N at most, i.e. roughness " + os.str()), std::string::npos) << d->message;
  EXPECT_NE(d->suggestion.find("reaches roughness " + os.str() + " at most"), std::string::npos) << d->suggestion;
  EXPECT_FALSE(r.program.has_value());  // never a silent clamp
}

TEST(DeviceCompile, AWeakerDeviceRefusesWhatAStrongerOneReaches) {
  // A device file for a weak joystick, 2 N, beside the shipped ones.
  fs::path dir = fs::path(test::temp_dir("weak-device")) / "calibration";
  fs::copy(fs::path(SANDPAPER_SOURCE_DIR) / "calibration", dir, fs::copy_options::recursive);
  std::ifstream in(dir / "devices/openffboard-2axis.toml");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  text.replace(text.find("name = \"openffboard-2axis\""), 26, "name = \"weak-2n\"");
  text.replace(text.find("max_continuous = \"10 N\""), 23, "max_continuous = \"2 N\"");
  std::ofstream(dir / "devices/weak-2n.toml") << text;

  auto weak = for_device("weak-2n", dir);
  auto strong = for_device("sandpaper-1995", dir);
  auto a = strong.compile_text("like corduroy; roughness 0.8");  // 2.8 N
  auto b = weak.compile_text("like corduroy; roughness 0.8");
  EXPECT_TRUE(a.ok());
  ASSERT_FALSE(b.ok());
  const auto* d = find_code(b, "E0310");
  ASSERT_NE(d, nullptr);
  double best = weak.calibration().roughness_map().percept_of(2.0);  // (2 / 3.746)^0.7596 = 0.621
  EXPECT_NEAR(best, std::pow(2.0 / (382 * 9.80665e-3), 0.759593), 1e-9);
  std::ostringstream os;
  os << std::floor(best * 1000) / 1000;  // shown rounded down, so that what is shown is reachable
  EXPECT_NE(d->message.find("roughness " + os.str()), std::string::npos) << d->message;
  // What it says it can reach, it compiles.
  EXPECT_TRUE(weak.compile_text("like corduroy; roughness " + os.str()).ok());
}

TEST(DeviceCompile, ResolutionCoarserThanAJndWarnsWithTheLeastResolvedRoughness) {
  auto thesis = for_device("sandpaper-1995");
  // 0.02 on the ratio scale is 21.7 mN: a 4.8 mN step is 22 %, more than a 12.5 % JND.
  auto r = thesis.compile_text("grating period 2 mm; roughness 0.02");
  ASSERT_TRUE(r.ok());
  const auto* w = find_code(r, "W0311");
  ASSERT_NE(w, nullptr);
  const auto& cal = thesis.calibration();
  double f_min = thesis.device().force_step_N(0) / cal.knowledge().force_jnd.weber_fraction;
  std::ostringstream os;
  os << std::ceil(cal.roughness_map().percept_of(f_min) * 1e4) / 1e4;  // three digits, rounded up: 0.0309
  EXPECT_NE(w->suggestion.find("from roughness " + os.str()), std::string::npos) << w->suggestion;
  // A finer device (1 mN steps) and a continuous one resolve it; a stronger material on the thesis
  // joystick is resolved too.
  EXPECT_FALSE(has_code(for_device("openffboard-2axis").compile_text("grating period 2 mm; roughness 0.02"), "W0311"));
  EXPECT_FALSE(has_code(for_device("sim").compile_text("grating period 2 mm; roughness 0.02"), "W0311"));
  EXPECT_FALSE(has_code(thesis.compile_text("grating period 2 mm; roughness 0.1"), "W0311"));
}

TEST(DeviceCompile, UncalibratedDeviceWarnsAndSaysHowToCalibrate) {
  auto r = for_device("openffboard-2axis").compile_text("corduroy");
  ASSERT_TRUE(r.ok());
  const auto* w = find_code(r, "W0331");
  ASSERT_NE(w, nullptr);
  EXPECT_NE(w->suggestion.find("sandpaper calibrate device"), std::string::npos);
  EXPECT_FALSE(r.program->command.calibrated);
  EXPECT_FALSE(has_code(for_device("sandpaper-1995").compile_text("corduroy"), "W0331"));
  EXPECT_FALSE(has_code(for_device("sim").compile_text("corduroy"), "W0331"));
}

}  // namespace
}  // namespace sandpaper
