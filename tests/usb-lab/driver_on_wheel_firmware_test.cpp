// Sandpaper's HID PID driver (runtime/usb) on the OpenFFBoard firmware's own 1-axis wheel, compiled
// for the host (usb-lab/firmware), in one process: the driver's reports reach the firmware's USB
// callbacks as the device stack would hand them over, with no bus between. What the guest lab adds
// (Linux's USB stack, usbhid, timing) is tested there; this is the two programs' agreement.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include "firmware_driving.hpp"
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/runtime/usb/hid_pid_joystick.hpp"

namespace sandpaper::usb_lab {

OpenFFBoardFirmware& firmware() { return started_once(MainClass::Wheel); }

namespace {

namespace usb = runtime::usb;
using usb::UsbStatus;

// The firmware as a UsbTransport: control requests on its control pipe (HID 1.11 section 7.2),
// output reports on its interrupt OUT endpoint, input reports from its interrupt IN queue.
class FirmwareTransport final : public usb::UsbTransport {
 public:
  UsbStatus report_descriptor(std::vector<std::uint8_t>& descriptor) override {
    const ControlReply r = firmware().control(SetupPacket{0x81, 0x06, 0x2200, 0, 4096}, {});
    if (r.stall) return UsbStatus::Stalled;
    descriptor = r.data;
    return UsbStatus::Ok;
  }
  UsbStatus detach_kernel_driver() override { return UsbStatus::Ok; }
  UsbStatus attach_kernel_driver() override { return UsbStatus::Ok; }
  UsbStatus claim_interface() override { return UsbStatus::Ok; }
  UsbStatus release_interface() override { return UsbStatus::Ok; }
  UsbStatus read_input(std::span<std::uint8_t> buffer, std::size_t& length, unsigned timeout_ms) noexcept override {
    std::vector<std::uint8_t> report;
    if (!firmware().next_interrupt_in(report, std::chrono::milliseconds(timeout_ms))) return UsbStatus::Timeout;
    firmware().interrupt_in_done(true);
    length = std::min(report.size(), buffer.size());
    std::copy_n(report.begin(), length, buffer.begin());
    return UsbStatus::Ok;
  }
  UsbStatus write_output(std::span<const std::uint8_t> report) noexcept override {
    firmware().interrupt_out(report);
    return UsbStatus::Ok;
  }
  UsbStatus set_feature(std::span<const std::uint8_t> report) override {
    const SetupPacket s{0x21, 0x09, static_cast<std::uint16_t>(0x0300 | report[0]), 0,
                        static_cast<std::uint16_t>(report.size())};
    return firmware().control(s, report).stall ? UsbStatus::Stalled : UsbStatus::Ok;
  }
  UsbStatus get_feature(std::uint8_t id, std::span<std::uint8_t> buffer, std::size_t& length) override {
    const SetupPacket s{0xA1, 0x01, static_cast<std::uint16_t>(0x0300 | id), 0, static_cast<std::uint16_t>(buffer.size())};
    const ControlReply r = firmware().control(s, {});
    if (r.stall) return UsbStatus::Stalled;
    length = std::min(r.data.size(), buffer.size());
    std::copy_n(r.data.begin(), length, buffer.begin());
    return UsbStatus::Ok;
  }
};

const calibration::DeviceCalibration& device_file(const char* name) {
  static const auto set = calibration::CalibrationSet::load(std::filesystem::path(SANDPAPER_SOURCE_DIR) / "calibration");
  return *set.find_device(name);
}

usb::HidPidOptions synchronous() {
  usb::HidPidOptions o;
  o.io = usb::HidPidIo::CallingThread;
  o.read_timeout_ms = 50;
  return o;
}

TEST(DriverOnWheelFirmware, AForceAlongTheRimTurnsTheWheelsMotorAsTheDeviceFileSays) {
  firmware().set_position(0, 0.0);
  FirmwareTransport t;
  usb::HidPidJoystick wheel(t, device_file("openffboard-wheel"), synchronous());
  EXPECT_EQ(wheel.effect_block_index(1), 0) << "one effect";
  ASSERT_TRUE(eventually([](const FirmwareState& s) { return s.effects_in_use == 1 && s.torque[0] == 0; }, kSettle));
  // command_sense -1: a positive force (toward +x along the rim) is a negative magnitude, which the
  // firmware turns into a negative driver torque, and a negative torque turns toward increasing
  // position (openffboard-wheel.toml; the joystick's X, the same chain, measured in the lab:
  // usb-lab.direction).
  ASSERT_TRUE(wheel.write_force_rt({3.0, 5.0}));
  EXPECT_TRUE(eventually([](const FirmwareState& s) { return s.torque[0] < 0; }, kSettle))
      << "torque " << firmware().state().torque[0];
  ASSERT_TRUE(wheel.write_force_rt({-3.0, 0.0}));
  EXPECT_TRUE(eventually([](const FirmwareState& s) { return s.torque[0] > 0; }, kSettle))
      << "torque " << firmware().state().torque[0];
  ASSERT_TRUE(wheel.write_force_rt({0.0, -5.0}));
  EXPECT_TRUE(eventually([](const FirmwareState& s) { return s.torque[0] == 0; }, kSettle));
  EXPECT_EQ(firmware().state().torque_updates[1], 0u) << "no second motor";
}

TEST(DriverOnWheelFirmware, ThePositionIsMillimetresOfRim) {
  const auto& file = device_file("openffboard-wheel");
  firmware().set_position(0, 0.5);  // a quarter of the way round from centre to lock: 225 deg
  FirmwareTransport t;
  usb::HidPidJoystick wheel(t, file, synchronous());
  glm::dvec2 p{0, 1};
  double t_s = 0;
  // The input reports come when a value changed, else every 101 ms: read until one is there.
  for (int i = 0; i < 40 && !(std::abs(p.x) > 0); ++i) ASSERT_TRUE(wheel.read_position_rt(t_s += 0.001, p));
  // Half of the positive range is a quarter of the rim's arc: 225 deg of a 150 mm rim = 589 mm.
  const double quarter_m = 0.25 * file.workspace_size_m[0];
  EXPECT_NEAR(p.x, quarter_m, 2 * file.position_resolution_m);
  EXPECT_NEAR(p.x / 1e-3 * file.wheel_deg_per_mm(), 225.0, 0.1);
  EXPECT_EQ(p.y, 0.0);
}

TEST(DriverOnWheelFirmware, TheJoysticksDeviceFileIsRefusedBeforeAnyEffect) {
  FirmwareTransport t;
  try {
    usb::HidPidJoystick joystick(t, device_file("openffboard-2axis"), synchronous());
    ADD_FAILURE() << "the wheel opened with the joystick's device file";
  } catch (const usb::HidPidError& e) {
    EXPECT_NE(std::string(e.what()).find("one axis"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(eventually([](const FirmwareState& s) { return s.effects_in_use == 0; }, kSettle));
}

}  // namespace
}  // namespace sandpaper::usb_lab
