// The application API (api/include/sandpaper/sandpaper.hpp): compiling by name, errors as data,
// playing, stopping and swapping on the simulated joystick.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>

#include "sandpaper/compiler/data_dirs.hpp"
#include "sandpaper/sandpaper.hpp"

namespace {

using sandpaper::CompileError;
using sandpaper::Library;
using sandpaper::Player;
using sandpaper::UnknownLevel;
using sandpaper::runtime::StopCause;

const Library& shipped() {
  static const Library library;
  return library;
}

TEST(Api, CompilesALibraryEntryByNameAsTheStatementsDo) {
  auto by_name = shipped().compile("corduroy");
  auto spelled = shipped().compile("like corduroy");
  EXPECT_EQ(by_name.name(), "corduroy");
  EXPECT_GT(by_name.compiled_max_lateral_force_N(), 0.0);
  EXPECT_DOUBLE_EQ(by_name.compiled_max_lateral_force_N(), spelled.compiled_max_lateral_force_N());
  // A roughness asked for changes the force through the map: 0.6 is rougher than corduroy's 0.45.
  auto rougher = shipped().compile("like corduroy; roughness 0.6");
  EXPECT_NEAR(rougher.compiled_roughness(), 0.6, 1e-6);
  EXPECT_GT(rougher.compiled_max_lateral_force_N(), by_name.compiled_max_lateral_force_N());
}

TEST(Api, BarePerceptualDescriptionStartsFromTheReferenceTexture) {
  auto m = shipped().compile("roughness 0.6");
  EXPECT_NEAR(m.compiled_roughness(), 0.6, 1e-6);
  EXPECT_GT(m.compiled_max_lateral_force_N(), 0.0);
}

TEST(Api, RoughnessLevelIsTheCalibratedLevel) {
  auto coarse = shipped().roughness_level("coarse");
  EXPECT_DOUBLE_EQ(shipped().roughness_level_value("coarse"), 0.5598);
  EXPECT_NEAR(coarse.compiled_roughness(), 0.5598, 1e-6);
  EXPECT_LT(shipped().roughness_level("fine").compiled_max_lateral_force_N(), coarse.compiled_max_lateral_force_N());
  auto levels = shipped().roughness_levels();
  EXPECT_EQ(levels.front(), "very-fine");
  EXPECT_EQ(levels.back(), "very-coarse");
}

// Levels of the other calibrated dimensions: each compiles alone, through its map, to the physical
// quantity the levels file places it at (20 N/m * 0.630957^(-1/0.8) = 35.57 N/m; 0.43 / 1 = 0.43).
TEST(Api, EveryCalibratedDimensionHasNamedLevels) {
  EXPECT_EQ(shipped().levels("viscosity"), (std::vector<std::string>{"very-thin", "thin", "medium", "thick", "very-thick"}));
  EXPECT_DOUBLE_EQ(shipped().level_value("softness", "soft"), 0.630957);
  const auto provenance = [](const sandpaper::Material& m, const std::string& name) {
    for (const auto& p : m.program().provenance)
      if (p.parameter == name) return p.value_si;
    return -1.0;
  };
  EXPECT_NEAR(provenance(shipped().level("softness", "soft"), "spring.stiffness"), 35.566, 1e-3);
  EXPECT_NEAR(provenance(shipped().level("slipperiness", "very-slippery"), "friction.coefficient"), 0.43, 1e-9);
  EXPECT_GT(provenance(shipped().level("viscosity", "very-thick"), "damper.damping"),
            provenance(shipped().level("viscosity", "thick"), "damper.damping"));
  try {
    shipped().level("bumpiness", "big");
    FAIL() << "no exception";
  } catch (const UnknownLevel& e) {
    // The percept is what is unknown; the ones with levels are calibration/levels/'s four files.
    EXPECT_NE(std::string(e.what()).find("unknown percept \"bumpiness\": no levels are named for it; percepts with levels: "
                                         "roughness, slipperiness, softness, viscosity"),
              std::string::npos)
        << e.what();
    EXPECT_TRUE(e.known().empty());
  }
  EXPECT_THROW(shipped().level("softness", "soft; spring 100 N/m"), UnknownLevel);
}

TEST(Api, UnknownLevelNamesTheKnownOnes) {
  try {
    shipped().roughness_level("corse");
    FAIL() << "no exception";
  } catch (const UnknownLevel& e) {
    EXPECT_EQ(e.name(), "corse");
    EXPECT_EQ(e.known(), shipped().roughness_levels());
    std::string what = e.what();
    EXPECT_NE(what.find("very-fine, fine, medium, coarse, very-coarse"), std::string::npos) << what;
    EXPECT_NE(what.find("did you mean \"coarse\""), std::string::npos) << what;
  }
  // Not a way to smuggle statements in: only level names are accepted.
  EXPECT_THROW(shipped().roughness_level("coarse; spring 100 N/m"), UnknownLevel);
}

TEST(Api, FailedCompileThrowsTheFormattedDiagnostics) {
  try {
    shipped().compile("like corduroy; roughnes 0.6");
    FAIL() << "no exception";
  } catch (const CompileError& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("<compile>:1:16: error[E0202]"), std::string::npos) << what;
    EXPECT_NE(what.find("^~~~~~~~"), std::string::npos) << what;
    EXPECT_NE(what.find("help: did you mean `roughness`?"), std::string::npos) << what;
    ASSERT_TRUE(e.diagnostics().has_errors());
    EXPECT_EQ(e.diagnostics().all().front().code, "E0202");
  }
  EXPECT_THROW(shipped().compile("no-such-material-anywhere"), CompileError);
}

TEST(Api, MissingDataDirectoryIsNamed) {
  try {
    Library library("/nonexistent/sandpaper-library");
    FAIL() << "no exception";
  } catch (const sandpaper::Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/sandpaper-library"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("SANDPAPER_LIBRARY"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Library(sandpaper::LibraryOptions{.library_dir = {}, .calibration_dir = {}, .device = "no-such-device", .library_path = {}}),
               sandpaper::Error);
}

// Sets an environment variable for one scope (tests run one per process under ctest).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    value ? ::setenv(name, value, 1) : ::unsetenv(name);
  }
  ~ScopedEnv() { old_ ? ::setenv(name_, old_->c_str(), 1) : ::unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(Api, EveryMissingDataDirectoryIsNamedAtOnceWithWhatChoseIt) {
  ScopedEnv lib("SANDPAPER_LIBRARY", nullptr), cal("SANDPAPER_CALIBRATION", nullptr);
  ScopedEnv data("SANDPAPER_DATA_DIR", "/nonexistent/sandpaper-data");
  try {
    Library library;
    FAIL() << "no exception";
  } catch (const sandpaper::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no library directory at /nonexistent/sandpaper-data/library (chosen by $SANDPAPER_DATA_DIR)"),
              std::string::npos) << what;
    EXPECT_NE(what.find("no calibration directory at /nonexistent/sandpaper-data/calibration (chosen by "
                        "$SANDPAPER_DATA_DIR)"), std::string::npos) << what;
    EXPECT_NE(what.find("Set SANDPAPER_DATA_DIR"), std::string::npos) << what;
  }
}

TEST(Api, DataDirectoryOverridesApplyMostSpecificFirst) {
  const std::string src = SANDPAPER_SOURCE_DIR;
  ScopedEnv lib("SANDPAPER_LIBRARY", nullptr), cal("SANDPAPER_CALIBRATION", nullptr);
  {
    ScopedEnv data("SANDPAPER_DATA_DIR", src.c_str());  // the source tree holds library/ and calibration/
    EXPECT_EQ(sandpaper::compiler::find_library_dir().dir, std::filesystem::path(src) / "library");
    EXPECT_EQ(sandpaper::compiler::find_library_dir().chosen_by, "$SANDPAPER_DATA_DIR");
    EXPECT_EQ(Library().calibration_dir(), std::filesystem::path(src) / "calibration");
    ScopedEnv only_lib("SANDPAPER_LIBRARY", (src + "/examples").c_str());
    EXPECT_EQ(sandpaper::compiler::find_library_dir().dir, std::filesystem::path(src) / "examples");
    EXPECT_EQ(sandpaper::compiler::find_library_dir().chosen_by, "$SANDPAPER_LIBRARY");
    EXPECT_EQ(sandpaper::compiler::find_calibration_dir().chosen_by, "$SANDPAPER_DATA_DIR");
  }
  ScopedEnv data("SANDPAPER_DATA_DIR", nullptr);
  EXPECT_EQ(sandpaper::compiler::find_library_dir().chosen_by, "the built-in default");
  EXPECT_EQ(sandpaper::compiler::find_library_dir().dir, std::filesystem::path(src) / "library");
}

TEST(Api, PlaysForTheDurationWithTheCompiledForce) {
  auto m = shipped().compile("corduroy");
  Player player = Player::simulated();
  player.load(m);
  player.start({.rate_hz = 1000, .duration_s = 0.3});
  auto report = player.wait();
  EXPECT_EQ(report.stop_cause, StopCause::Completed);
  EXPECT_EQ(report.ticks, 300u);
  EXPECT_GT(report.felt_max_lateral_force_N, 0.5 * m.compiled_max_lateral_force_N());
  EXPECT_LE(report.felt_max_lateral_force_N, m.compiled_max_lateral_force_N() * (1 + 1e-9));
  EXPECT_FALSE(player.playing());
}

TEST(Api, PlaysUntilStoppedAndSwapsWhilePlaying) {
  Player player = Player::simulated();
  player.load(shipped().roughness_level("very-fine"));
  player.start();  // no duration: until stop()
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_TRUE(player.playing());
  const auto strong = shipped().roughness_level("very-coarse");
  player.load(strong);  // swapped on the servo thread
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  auto report = player.stop();
  EXPECT_EQ(report.stop_cause, StopCause::StopRequested);
  EXPECT_GT(report.ticks, 0u);
  // Only the very-coarse material reaches above the very-fine one's maximum.
  EXPECT_GT(report.felt_max_lateral_force_N, shipped().roughness_level("very-fine").compiled_max_lateral_force_N() * 1.5);
  EXPECT_FALSE(player.playing());
}

TEST(Api, PlayerRefusesToStartWithNothingLoadedOrTwice) {
  Player player = Player::simulated();
  EXPECT_THROW(player.start(), sandpaper::Error);
  EXPECT_THROW(player.stop(), sandpaper::Error);
  player.load(shipped().compile("corduroy"));
  EXPECT_THROW(player.start({.rate_hz = 50, .duration_s = 0.1}), std::invalid_argument);  // below 900 Hz
  player.start();
  EXPECT_THROW(player.start(), sandpaper::Error);
  EXPECT_EQ(player.stop().stop_cause, StopCause::StopRequested);
}

// With a calibrated joystick plugged in, usb() opens it and names the calibration to compile for;
// without one (CI has no USB bus) it throws DeviceError naming the joysticks the calibration knows.
TEST(Api, UsbPlayerOpensACalibratedJoystickOrSaysWhichItKnows) {
  EXPECT_EQ(Player::simulated().device_calibration(), "");
  try {
    Player player = Player::usb(shipped());
    EXPECT_FALSE(player.device_calibration().empty());
  } catch (const sandpaper::DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("openffboard-2axis (1209:ffb0)"), std::string::npos) << e.what();
  }
}

// Player::open takes the factory's paths to a joystick on the bus; a node that is not there, or a
// device that is not on the bus, is a DeviceError that says so.
TEST(Api, OpenPlaysAJoystickAlongTheNamedPathOnly) {
  try {
    Player player = Player::open(shipped(), "hidraw:/nonexistent/hidraw9");
    ADD_FAILURE() << "opened a node that does not exist";
  } catch (const sandpaper::DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("no hidraw node /nonexistent/hidraw9"), std::string::npos) << e.what();
  }
  try {
    Player player = Player::open(shipped(), "sim");
    ADD_FAILURE() << "Player::open took the simulated joystick";
  } catch (const sandpaper::DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("the simulated joystick has a player of its own"), std::string::npos) << e.what();
  }
  // uncalibrated is for an input event node alone: asked along another path, it is refused, not ignored.
  try {
    Player player = Player::open(shipped(), "hidraw", {.uncalibrated = true});
    ADD_FAILURE() << "uncalibrated taken through hidraw";
  } catch (const sandpaper::DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("--uncalibrated plays an input event node"), std::string::npos) << e.what();
  }
  try {
    Player player = Player::open(shipped(), "evdev:/nonexistent/event99", {.uncalibrated = true});
    ADD_FAILURE() << "opened an event node that does not exist";
  } catch (const sandpaper::DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/event99"), std::string::npos) << e.what();
  }
  EXPECT_EQ(Player::simulated().warning(), "");
}

}  // namespace
