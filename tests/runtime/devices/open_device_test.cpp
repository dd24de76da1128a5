// The device factory: which family opens which device calibration, what each refuses, and that a
// device opened here is the one its calibration file describes (runtime/devices/open_device.hpp).
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "sandpaper/runtime/devices/open_device.hpp"
#include "sandpaper/runtime/dummy_joystick.hpp"
#include "sandpaper/runtime/evdev/evdev_joystick.hpp"
#include "sandpaper/runtime/recording_device.hpp"

namespace sandpaper::runtime {
namespace {

namespace fs = std::filesystem;
using Cause = DeviceOpenError::Cause;

const calibration::CalibrationSet& shipped() {
  static const auto set = calibration::CalibrationSet::load(fs::path(SANDPAPER_SOURCE_DIR) / "calibration");
  return set;
}

DeviceSpec spec_for(const std::string& device) {
  DeviceSpec spec;
  spec.device = device;
  return spec;
}

// The cause open_device throws for `spec`, or nothing when it opens.
std::optional<Cause> refusal(const calibration::CalibrationSet& set, DeviceSpec spec, std::string* message = nullptr) {
  try {
    (void)open_device(set, std::move(spec));
  } catch (const DeviceOpenError& e) {
    if (message) *message = e.what();
    return e.cause;
  }
  return std::nullopt;
}

TEST(OpenDevice, SimIsTheSimulatedJoystickWithTheLimitsOfItsFile) {
  DeviceSpec spec = spec_for("sim");
  spec.record_ticks = 10;
  const OpenedDevice d = open_device(shipped(), spec);
  EXPECT_STREQ(d.family, "simulated");
  EXPECT_FALSE(d.real);
  EXPECT_EQ(d.calibration, "sim");
  ASSERT_NE(d.recording, nullptr);
  EXPECT_EQ(d.pointer, nullptr);
  EXPECT_FALSE(d.emulation);
  // calibration/devices/sim.toml: 10 N, 900-10000 Hz, a 9 inch circle (Minsky 1995 Table 2).
  EXPECT_DOUBLE_EQ(d.device->limits().max_force_N, 10.0);
  EXPECT_DOUBLE_EQ(d.device->limits().min_rate_hz, 900.0);
  EXPECT_DOUBLE_EQ(d.device->limits().max_rate_hz, 10000.0);
  EXPECT_NEAR(d.device->limits().workspace_radius_m, 4.5 * 0.0254, 1e-12);
  // And the runtime's built-in simulated limits, which tests and Player::simulated use, are the same.
  const DeviceLimits builtin = sim_device_limits();
  EXPECT_DOUBLE_EQ(builtin.max_force_N, d.device->limits().max_force_N);
  EXPECT_DOUBLE_EQ(builtin.min_rate_hz, d.device->limits().min_rate_hz);
  EXPECT_DOUBLE_EQ(builtin.max_rate_hz, d.device->limits().max_rate_hz);
  EXPECT_NEAR(builtin.workspace_radius_m, d.device->limits().workspace_radius_m, 1e-12);
  EXPECT_EQ(d.description, "position-controlled hand");
}

TEST(OpenDevice, TheScriptedHandMovesTheSimulatedHandle) {
  DeviceSpec spec = spec_for("sim");
  spec.script = HandScript{HandPath::Scan, 0.05, 0.03, 0, 0};
  spec.record_ticks = 2;
  OpenedDevice d = open_device(shipped(), spec);
  glm::dvec2 p{1, 1};
  ASSERT_TRUE(d.device->read_position_rt(0.1, p));
  EXPECT_NEAR(p.x, 0.005, 1e-12);  // 50 mm/s for 0.1 s from the centre, heading +x
  EXPECT_NEAR(p.y, 0.0, 1e-12);
}

TEST(OpenDevice, The1995JoystickIsEmulatedWithItsQuantisation) {
  DeviceSpec spec = spec_for("sandpaper-1995");
  spec.record_ticks = 4;
  const OpenedDevice d = open_device(shipped(), spec);
  EXPECT_STREQ(d.family, "emulated");
  ASSERT_TRUE(d.emulation);
  ASSERT_NE(d.recording, nullptr);
  // Minsky 1995 Table 6: one joystick unit is 0.490909 gram-force; Table 2: 12-bit positions across 9 inches.
  EXPECT_NEAR(d.emulation->quantization.force_step_N[0], 0.490909e-3 * 9.80665, 1e-6);
  EXPECT_NEAR(d.emulation->quantization.position_step_m, 9 * 0.0254 / 4096, 1e-7);
  EXPECT_EQ(d.emulation->quantization.command_max, 2048);
  EXPECT_EQ(d.emulation->tables, TableSampling::Hold);
  // The device itself quantises: a force of 1.001 command units is sent as one.
  const double unit = d.emulation->quantization.force_step_N[0];
  glm::dvec2 p;
  ASSERT_TRUE(d.device->read_position_rt(0, p));
  ASSERT_TRUE(d.device->write_force_rt({1.4 * unit, 0}));
  ASSERT_EQ(d.recording->records().size(), 1u);
  EXPECT_NEAR(d.recording->records()[0].force_N.x, unit, 1e-12);
}

TEST(OpenDevice, TheStudiosPointerMovesADummyHandleAndOnlyOnTheSimulatedJoystick) {
  DeviceSpec spec = spec_for("sim");
  spec.hand = SimulatedHand::Pointer;
  const OpenedDevice d = open_device(shipped(), spec);
  ASSERT_NE(d.pointer, nullptr);
  EXPECT_EQ(d.recording, nullptr);
  EXPECT_EQ(static_cast<Device*>(d.pointer), d.device.get());
  spec.device = "sandpaper-1995";
  EXPECT_EQ(refusal(shipped(), spec), Cause::WrongOptions);
}

TEST(OpenDevice, ReplayPlaysTheGivenPositionsOnePerTick) {
  DeviceSpec spec = spec_for("sim");
  spec.hand = SimulatedHand::Replay;
  spec.replay_positions_m = {{0.001, 0}, {0.002, 0.001}, {0.003, 0.002}};
  spec.replay_name = "trace.csv";
  OpenedDevice d = open_device(shipped(), spec);
  EXPECT_EQ(d.description, "replay of trace.csv");
  glm::dvec2 p;
  ASSERT_TRUE(d.device->read_position_rt(0, p));
  ASSERT_TRUE(d.device->write_force_rt({0, 0}));
  ASSERT_TRUE(d.device->read_position_rt(0.001, p));
  EXPECT_DOUBLE_EQ(p.x, 0.002);
  EXPECT_DOUBLE_EQ(p.y, 0.001);
}

TEST(OpenDevice, TheDynamicHandIsDescribedByItsModel) {
  DeviceSpec spec = spec_for("sim");
  spec.hand = SimulatedHand::Dynamic;
  const OpenedDevice d = open_device(shipped(), spec);
  EXPECT_EQ(d.description, "dynamic hand (0.554 kg, 135 N/m, 6.45 N*s/m)");
}

TEST(OpenDevice, AWatchdogIsRefusedOnSimulatedDevices) {
  for (const char* name : {"sim", "sandpaper-1995"}) {
    DeviceSpec spec = spec_for(name);
    spec.watchdog_s = 0.5;
    std::string message;
    EXPECT_EQ(refusal(shipped(), spec, &message), Cause::WrongOptions) << name;
    EXPECT_NE(message.find("--watchdog applies to --device usb"), std::string::npos) << message;
    EXPECT_THROW((void)choose_device(shipped(), spec), DeviceOpenError) << name;
  }
}

TEST(OpenDevice, AnUnknownNameListsTheDevicesThereAre) {
  std::string message;
  EXPECT_EQ(refusal(shipped(), spec_for("nosuch"), &message), Cause::UnknownDevice);
  EXPECT_NE(message.find("'nosuch'"), std::string::npos) << message;
  EXPECT_NE(message.find("sandpaper-1995"), std::string::npos) << message;
  EXPECT_NE(message.find("openffboard-2axis"), std::string::npos) << message;
}

TEST(OpenDevice, SimulatedHandsAndTheVirtualClockAreRefusedOnAUsbJoystickBeforeUsbIsSearched) {
  DeviceSpec clock = spec_for("usb");
  clock.virtual_clock = true;
  std::string message;
  EXPECT_EQ(refusal(shipped(), clock, &message), Cause::WrongOptions);
  EXPECT_NE(message.find("real time"), std::string::npos) << message;
  for (SimulatedHand hand : {SimulatedHand::Replay, SimulatedHand::Dynamic}) {
    DeviceSpec spec = spec_for("openffboard-2axis");
    spec.hand = hand;
    EXPECT_EQ(refusal(shipped(), spec), Cause::WrongOptions);
  }
}

// A lab's device file with neither [usb] nor [emulation] has no driver, but can be simulated with its limits.
TEST(OpenDevice, ADeviceWithoutADriverIsRefusedUnlessSimulated) {
  const fs::path dir = fs::temp_directory_path() / ("sandpaper-open-device-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::copy(fs::path(SANDPAPER_SOURCE_DIR) / "calibration", dir, fs::copy_options::recursive);
  std::ifstream in(dir / "devices" / "openffboard-2axis.toml");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  text.replace(text.find("name = \"openffboard-2axis\""), 26, "name = \"lab-stick\"");
  text.erase(text.find("[usb]"), text.find("[firmware]") - text.find("[usb]"));
  std::ofstream(dir / "devices" / "lab-stick.toml") << text;
  const auto set = calibration::CalibrationSet::load(dir);
  fs::remove_all(dir);
  std::string message;
  EXPECT_EQ(refusal(set, spec_for("lab-stick"), &message), Cause::NoDriver);
  EXPECT_NE(message.find("neither a [usb] table"), std::string::npos) << message;
  DeviceSpec simulated = spec_for("lab-stick");
  simulated.simulate = true;
  const OpenedDevice d = open_device(set, simulated);
  EXPECT_STREQ(d.family, "simulated");
  EXPECT_EQ(d.calibration, "lab-stick");
  EXPECT_NEAR(d.device->limits().workspace_radius_m, 0.05, 1e-12);  // half the 100 mm square's side
  const DeviceChoice choice = choose_device(set, simulated);
  EXPECT_EQ(choice.calibration, "lab-stick");
  EXPECT_FALSE(choice.real);
}

TEST(OpenDevice, ChoosingADeviceOpensNothing) {
  const DeviceChoice emulated = choose_device(shipped(), spec_for("sandpaper-1995"));
  EXPECT_EQ(emulated.calibration, "sandpaper-1995");
  EXPECT_STREQ(emulated.family, "emulated");
  EXPECT_FALSE(emulated.real);
}

// With a calibrated joystick plugged in it opens; without one (CI has no USB bus) the error names
// the joysticks the calibration knows.
TEST(OpenDevice, UsbOpensAKnownJoystickOrNamesTheKnownOnes) {
  try {
    const OpenedDevice d = open_device(shipped(), spec_for("usb"));
    EXPECT_TRUE(d.real);
    EXPECT_STREQ(d.family, "usb");
    ASSERT_TRUE(d.usb);
    EXPECT_NE(d.usb_joystick, nullptr);
  } catch (const DeviceOpenError& e) {
    EXPECT_TRUE(e.cause == Cause::NoUsb || e.cause == Cause::NoCalibration || e.cause == Cause::AccessDenied) << e.what();
    if (e.cause == Cause::NoUsb) {
      EXPECT_NE(std::string(e.what()).find("openffboard-2axis (1209:ffb0)"), std::string::npos) << e.what();
    }
  }
}

TEST(OpenDevice, HidrawIsFoundOnTheBusAndRefusesSimulatedHands) {
  DeviceSpec clock = spec_for("hidraw");
  clock.virtual_clock = true;
  std::string message;
  EXPECT_EQ(refusal(shipped(), clock, &message), Cause::WrongOptions);
  EXPECT_NE(message.find("real time"), std::string::npos) << message;
  DeviceSpec dynamic = spec_for("hidraw:/dev/hidraw0");
  dynamic.hand = SimulatedHand::Dynamic;
  EXPECT_EQ(refusal(shipped(), dynamic), Cause::WrongOptions);
  // A path that is no hidraw node is named, not taken for a calibration's name.
  EXPECT_EQ(refusal(shipped(), spec_for("hidraw:/nonexistent/hidraw99"), &message), Cause::NoUsb);
  EXPECT_NE(message.find("no hidraw node /nonexistent/hidraw99"), std::string::npos) << message;
}

TEST(OpenDevice, EvdevIsFoundOnTheBusAndRefusesSimulatedHands) {
  DeviceSpec clock = spec_for("evdev");
  clock.virtual_clock = true;
  std::string message;
  EXPECT_EQ(refusal(shipped(), clock, &message), Cause::WrongOptions);
  EXPECT_NE(message.find("real time"), std::string::npos) << message;
  DeviceSpec replay = spec_for("evdev:/dev/input/event0");
  replay.hand = SimulatedHand::Replay;
  EXPECT_EQ(refusal(shipped(), replay), Cause::WrongOptions);
  // A path that is no force-feedback event node is named, not taken for a calibration's name nor
  // handed to the hidraw entry.
  EXPECT_EQ(refusal(shipped(), spec_for("evdev:/nonexistent/event99"), &message), Cause::NoUsb);
  EXPECT_NE(message.find("no input event node with force feedback at /nonexistent/event99"), std::string::npos) << message;
  // Resolved to its calibration, the path asked for still decides the family.
  DeviceSpec through = spec_for("openffboard-2axis");
  through.through = "evdev:/nonexistent/event99";
  EXPECT_EQ(refusal(shipped(), through, &message), Cause::NoUsb);
  EXPECT_NE(message.find("input event node"), std::string::npos) << message;
}

TEST(OpenDevice, TheUncalibratedProfileIsNoDeviceAndPlaysOnlyThroughEvdev) {
  const auto& set = shipped();
  const calibration::DeviceCalibration* profile = set.find_device(evdev::kUncalibratedProfile);
  ASSERT_NE(profile, nullptr) << "calibration/profiles/uncalibrated-evdev.toml";
  for (const auto& d : set.devices()) EXPECT_NE(d.name, profile->name) << "a profile is not listed among the devices";
  EXPECT_FALSE(profile->calibrated());
  EXPECT_EQ(profile->usb_vendor_id, -1) << "no [usb] table: no device is ever taken for it";
  EXPECT_EQ(profile->command_unit, evdev::kLevelUnit);
  // The conservative limit: a quarter of struct ff_constant_effect's level range (linux/input.h).
  EXPECT_EQ(profile->command_max * 4, 32768);
  EXPECT_NEAR(profile->max_force_N, 2.5, 1e-9);
  // Levels go out as they are, whatever the device's report descriptor says, and stop at the quarter.
  EXPECT_EQ(evdev::level_for_force(*profile, 0, 1.0, 0, 0), -3277) << "1 N at 10 N / 32767 a level, pushing as -1 says";
  EXPECT_EQ(evdev::level_for_force(*profile, 1, -1.0, 0, 0), 3277);
  EXPECT_EQ(evdev::level_for_force(*profile, 0, -10.0, 0, 0), 8192) << "10 N asked: a quarter of the range sent";
  EXPECT_EQ(evdev::level_for_force(*profile, 0, 1e9, 0, 0), -8192);
  // A device with a file of its own goes through hid-pidff's rescale of its Magnitude range
  // (the OpenFFBoard's -10000..10000): its full 10 N is its full range.
  const calibration::DeviceCalibration& own = *set.find_device("openffboard-2axis");
  EXPECT_EQ(evdev::command_for_level(evdev::level_for_force(own, 0, -10.0, -10000, 10000), -10000, 10000), 10000);
  // The profile is refused as a device, and --uncalibrated anywhere but evdev.
  std::string message;
  EXPECT_EQ(refusal(set, spec_for(evdev::kUncalibratedProfile), &message), Cause::WrongOptions);
  EXPECT_NE(message.find("--device evdev (or evdev:PATH) --uncalibrated"), std::string::npos) << message;
  DeviceSpec sim = spec_for("sim");
  sim.uncalibrated = true;
  EXPECT_EQ(refusal(set, sim, &message), Cause::WrongOptions);
  EXPECT_NE(message.find("--uncalibrated plays an input event node"), std::string::npos) << message;
  DeviceSpec hidraw = spec_for("hidraw");
  hidraw.uncalibrated = true;
  EXPECT_EQ(refusal(set, hidraw), Cause::WrongOptions);
  // Through evdev, it is accepted as far as the bus (no such node here).
  DeviceSpec missing = spec_for("evdev:/nonexistent/event99");
  missing.uncalibrated = true;
  EXPECT_EQ(refusal(set, missing, &message), Cause::NoUsb) << message;
  // Every caller says the same before it plays with the profile (its own 2.5 N and quarter range,
  // the file's figures above); a device's own file has nothing to say.
  const std::string warning = profile_warning(set, evdev::kUncalibratedProfile);
  EXPECT_NE(warning.find("no calibration file names this device"), std::string::npos) << warning;
  EXPECT_NE(warning.find("forces stop at 2.5 N"), std::string::npos) << warning;
  EXPECT_NE(warning.find("(8192 "), std::string::npos) << warning;
  EXPECT_NE(warning.find("sandpaper calibrate device"), std::string::npos) << warning;
  EXPECT_EQ(profile_warning(set, "openffboard-2axis"), "");
  EXPECT_EQ(profile_warning(set, "sim"), "");
  EXPECT_EQ(choose_device(set, spec_for("sim")).warning, "");
}

TEST(OpenDevice, TheUdevRuleNamesTheDeviceInLowerCaseHex) {
  EXPECT_EQ(usb_ids(0x1209, 0xFFB0), "1209:ffb0");
  EXPECT_EQ(udev_rule(0x1209, 0xFFB0),
            "SUBSYSTEM==\"usb\", ATTR{idVendor}==\"1209\", ATTR{idProduct}==\"ffb0\", MODE=\"0660\", TAG+=\"uaccess\"");
  EXPECT_NE(udev_help(0x1209, 0xFFB0).find("/etc/udev/rules.d/70-sandpaper.rules"), std::string::npos);
  // hidraw: the node of any interface of the USB device (ATTRS walks up to it), for the seat's user.
  EXPECT_EQ(hidraw_udev_rule(0x1209, 0xFFB0),
            "KERNEL==\"hidraw*\", ATTRS{idVendor}==\"1209\", ATTRS{idProduct}==\"ffb0\", TAG+=\"uaccess\"");
  EXPECT_EQ(known_usb_devices(shipped()), "openffboard-2axis (1209:ffb0), openffboard-wheel (1209:ffb0)");
}

}  // namespace
}  // namespace sandpaper::runtime
