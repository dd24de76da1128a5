#pragma once
// The hand-written OpenFFBoard-like descriptor (data/openffboard_like_2axis.hex), the shipped
// openffboard-2axis calibration and a 1 mN copy of it for that descriptor, and a fake transport
// primed with that device's replies.
#include <memory>

#include "fake_transport.hpp"
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/runtime/usb/hid_pid_joystick.hpp"

namespace sandpaper::runtime::usb::testing {

inline std::vector<std::uint8_t> test_descriptor() {
  return read_hex_file(std::filesystem::path(SANDPAPER_SOURCE_DIR) / "tests/runtime/usb/data/openffboard_like_2axis.hex");
}

// The shipped openffboard-2axis calibration.
inline const calibration::DeviceCalibration& shipped_openffboard() {
  static const auto set = calibration::CalibrationSet::load(std::filesystem::path(SANDPAPER_SOURCE_DIR) / "calibration");
  return *set.find_device("openffboard-2axis");
}

// The shipped openffboard-wheel calibration (one axis along the rim).
inline const calibration::DeviceCalibration& shipped_openffboard_wheel() {
  static const auto set = calibration::CalibrationSet::load(std::filesystem::path(SANDPAPER_SOURCE_DIR) / "calibration");
  return *set.find_device("openffboard-wheel");
}

// The shipped calibration on the hand-written descriptor's Magnitude range, -10000..10000, at 1 mN
// per command unit: the driver's arithmetic in round numbers. The shipped scale (10 N over the
// firmware's 32767) is tested against the real descriptor (openffboard_firmware_test.cpp).
inline const calibration::DeviceCalibration& openffboard() {
  static const auto like = [] {
    auto d = shipped_openffboard();
    d.command_max = 10000;
    for (auto& a : d.axis) a.newtons_per_command_unit = 0.001;
    return d;
  }();
  return like;
}

// Options for the driver making its transfers on the calling thread, so that a test sees the
// exact report stream tick by tick (HidPidIo::CallingThread).
inline HidPidOptions synchronous() {
  HidPidOptions o;
  o.io = HidPidIo::CallingThread;
  return o;
}

// Input report 1: buttons, X, Y (16-bit little-endian).
inline std::vector<std::uint8_t> position_report(std::int16_t x, std::int16_t y) {
  const auto ux = static_cast<std::uint16_t>(x), uy = static_cast<std::uint16_t>(y);
  return {0x01, 0x00, static_cast<std::uint8_t>(ux & 0xFF), static_cast<std::uint8_t>(ux >> 8),
          static_cast<std::uint8_t>(uy & 0xFF), static_cast<std::uint8_t>(uy >> 8)};
}

// A device that answers the driver's open: PID Pool (4 effects at once), Block Load success with
// block indices 1 then 2, and a first position report.
inline std::unique_ptr<FakeTransport> primed_transport() {
  auto t = std::make_unique<FakeTransport>(test_descriptor());
  t->add_feature_reply(0x13, {0x13, 0x00, 0x10, 0x04, 0x01});
  t->add_feature_reply(0x12, {0x12, 0x01, 0x01, 0x27, 0x00});
  t->add_feature_reply(0x12, {0x12, 0x02, 0x01, 0x26, 0x00});
  // Two: the driver takes the second as where the handle is now (the first may be stale).
  t->add_input({UsbStatus::Ok, position_report(0, 0)});
  t->add_input({UsbStatus::Ok, position_report(0, 0)});
  return t;
}

}  // namespace sandpaper::runtime::usb::testing
