// Which device file a plugged-in device is played with: by its USB ID and, where one board has two
// files (the OpenFFBoard as a joystick and as a wheel, both 1209:FFB0), by the axes its report
// descriptor's effects act on (UsbHidDeviceInfo::force_axes).
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "devices_internal.hpp"
#include "fake_transport.hpp"
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/runtime/evdev/evdev_node.hpp"
#include "sandpaper/runtime/usb/libusb_transport.hpp"

namespace sandpaper::runtime {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = SANDPAPER_SOURCE_DIR;

using usb::testing::read_hex_file;

TEST(CalibrationMatch, TheBoardsWheelAndJoystickAreToldApartByTheirEffectsAxes) {
  const auto set = calibration::CalibrationSet::load(kSource / "calibration");
  usb::UsbHidDeviceInfo joystick, wheel;
  usb::summarise_report_descriptor(read_hex_file(kSource / "tests/runtime/usb/data/openffboard_2axis.hex"), joystick);
  usb::summarise_report_descriptor(read_hex_file(kSource / "tests/runtime/usb/data/openffboard_1axis_wheel.hex"), wheel);
  ASSERT_TRUE(joystick.descriptor_read && wheel.descriptor_read);
  EXPECT_EQ(joystick.force_axes, 2);  // Set Effect's Axes Enable: X and Y
  EXPECT_EQ(wheel.force_axes, 1);     // X alone (usb_hid_1ffb_desc.c)
  EXPECT_EQ(usb_calibration_of(set, true, 0x1209, 0xFFB0, joystick.force_axes)->name, "openffboard-2axis");
  EXPECT_EQ(usb_calibration_of(set, true, 0x1209, 0xFFB0, wheel.force_axes)->name, "openffboard-wheel");
  // Not read: the first file by name, which the driver then checks against the descriptor.
  EXPECT_EQ(usb_calibration_of(set, true, 0x1209, 0xFFB0, 0)->name, "openffboard-2axis");
  EXPECT_EQ(usb_calibration_of(set, false, 0x1209, 0xFFB0, 1), nullptr);  // not on USB
  // A folder without the joystick's file (usb-lab.evdev-uncalibrated's): the joystick has no file,
  // rather than the wheel's, which would play its one axis.
  const fs::path without = fs::temp_directory_path() / ("sandpaper-match-cal-" + std::to_string(::getpid()));
  fs::remove_all(without);
  fs::copy(kSource / "calibration", without, fs::copy_options::recursive);
  fs::remove(without / "devices/openffboard-2axis.toml");
  const auto no_joystick = calibration::CalibrationSet::load(without);
  EXPECT_EQ(usb_calibration_of(no_joystick, true, 0x1209, 0xFFB0, 2), nullptr);
  EXPECT_EQ(usb_calibration_of(no_joystick, true, 0x1209, 0xFFB0, 1)->name, "openffboard-wheel");
  fs::remove_all(without);
  EXPECT_EQ(usb_calibration_of(set, true, 0x1209, 0xFFB1, 1), nullptr);

  // An event node reads its HID device's descriptor from sysfs (EvdevNode::report_descriptor).
  const fs::path dir = fs::temp_directory_path() / ("sandpaper-match-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto bytes = read_hex_file(kSource / "tests/runtime/usb/data/openffboard_1axis_wheel.hex");
  std::ofstream(dir / "report_descriptor", std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                                    static_cast<std::streamsize>(bytes.size()));
  evdev::EvdevNode node;
  node.report_descriptor = (dir / "report_descriptor").string();
  EXPECT_EQ(force_axes_of(node), 1);
  node.report_descriptor.clear();
  EXPECT_EQ(force_axes_of(node), 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sandpaper::runtime
