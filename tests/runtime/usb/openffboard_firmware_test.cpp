// The driver against the REAL OpenFFBoard descriptor (data/openffboard_2axis.hex), with every report it
// sends read back the way the firmware reads it: the packed structs of Ultrawipf/OpenFFBoard
// Firmware/FFBoard/Inc/ffb_defs.h (commit d19d616, cited ffb_defs.h:LINE) and the parsing in
// Firmware/FFBoard/Src/HidFFB.cpp (commit 3a4cc0e, cited HidFFB.cpp:LINE). Byte offsets count the
// report ID as byte 0. The expectations are the firmware's, not the driver's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "fake_transport.hpp"
#include "usb_test_support.hpp"

namespace sandpaper::runtime::usb {
namespace {

using testing::FakeTransport;
using testing::Op;
using Bytes = std::vector<std::uint8_t>;

std::uint16_t u16(const Bytes& b, std::size_t at) { return static_cast<std::uint16_t>(b[at] | (b[at + 1] << 8)); }
std::int16_t i16(const Bytes& b, std::size_t at) { return static_cast<std::int16_t>(u16(b, at)); }

// reportHID_t (ffb_defs.h:103-112): ID 1, 64 buttons, then X, Y, Z, Rx, Ry, Rz, Dial, Slider as int16.
Bytes position_report(std::int16_t x, std::int16_t y) {
  Bytes r(25, 0);
  r[0] = 0x01;
  r[9] = static_cast<std::uint8_t>(x & 0xFF);
  r[10] = static_cast<std::uint8_t>((x >> 8) & 0xFF);
  r[11] = static_cast<std::uint8_t>(y & 0xFF);
  r[12] = static_cast<std::uint8_t>((y >> 8) & 0xFF);
  return r;
}

// What the firmware answers (HidFFB.cpp:151-172, tinyusb prepending the report ID): PID Pool
// [0x13, pool size, 40 simultaneous effects, device-managed pool], Block Load [0x12, index, 1 = success, pool left].
std::unique_ptr<FakeTransport> openffboard_transport() {
  auto t = std::make_unique<FakeTransport>(
      testing::read_hex_file(std::filesystem::path(SANDPAPER_SOURCE_DIR) / "tests/runtime/usb/data/openffboard_2axis.hex"));
  t->add_feature_reply(0x13, {0x13, 0x00, 0x10, 40, 0x01});
  t->add_feature_reply(0x12, {0x12, 0x01, 0x01, 0x00, 0x10});
  t->add_feature_reply(0x12, {0x12, 0x02, 0x01, 0x00, 0x0F});
  t->add_input({UsbStatus::Ok, position_report(16384, -32767)});
  return t;
}

std::vector<Bytes> outputs_with_id(const FakeTransport& t, std::uint8_t id, Op op = Op::Output) {
  std::vector<Bytes> out;
  for (const auto& x : t.log())
    if (x.op == op && x.size > 0 && x.bytes[0] == id) out.push_back(x.data());
  return out;
}

// The axis factor the firmware gives a Set Effect (HidFFB.cpp:320-321): with Direction Enable,
// sin(angle) to X and -cos(angle) to Y of directionX (hundredths of a degree); without it, each
// enabled axis linearly by its own direction, X (dir - 18000) / 18000, Y -(dir - 18000) / 18000.
double axis_factor(const Bytes& set_effect, int axis) {
  const std::uint8_t enable = set_effect[13];
  if (enable & 0x04) {
    const double angle = u16(set_effect, 14) * std::numbers::pi / 18000;
    return axis == 0 ? std::sin(angle) : -std::cos(angle);
  }
  if (!(enable & (1 << axis))) return 0;
  const double dir = axis == 0 ? u16(set_effect, 14) : u16(set_effect, 16);
  return axis == 0 ? (dir - 18000) / 18000 : -(dir - 18000) / 18000;
}

TEST(OpenFFBoardFirmware, TheDriverOpensTheRealDescriptor) {
  auto t = openffboard_transport();
  HidPidJoystick joystick(*t, testing::shipped_openffboard(), testing::synchronous());
  EXPECT_EQ(joystick.effect_block_index(0), 1);
  EXPECT_EQ(joystick.effect_block_index(1), 2);
  glm::dvec2 p{0, 0};
  t->add_input({UsbStatus::Ok, position_report(16384, -32767)});
  ASSERT_TRUE(joystick.read_position_rt(0.0, p));
  // X, Y at bytes 9-10 and 11-12 (ffb_defs.h:105-106), -32767..32767 over the calibration's 100 mm.
  EXPECT_NEAR(p.x, 16384.0 / 32767.0 * 0.05, 1e-9);
  EXPECT_NEAR(p.y, -0.05, 1e-9);
}

TEST(OpenFFBoardFirmware, DeviceControlIsTheFirmwaresBitmask) {
  auto t = openffboard_transport();
  {
    HidPidJoystick joystick(*t, testing::shipped_openffboard(), testing::synchronous());
  }
  // HID_ID_CTRLREP 0x0C (ffb_defs.h:56); ffb_control(report[1]) reads bits: 0x01 enable, 0x02
  // disable, 0x04 stop all, 0x08 reset (HidFFB.cpp:97-99, 205-224). Open: reset, enable; close:
  // stop all, disable.
  const auto control = outputs_with_id(*t, 0x0C);
  ASSERT_EQ(control.size(), 4u);
  EXPECT_EQ(control[0], (Bytes{0x0C, 0x08}));
  EXPECT_EQ(control[1], (Bytes{0x0C, 0x01}));
  EXPECT_EQ(control[2], (Bytes{0x0C, 0x04}));
  EXPECT_EQ(control[3], (Bytes{0x0C, 0x02}));
}

TEST(OpenFFBoardFirmware, EffectsAreConstantForcesOnOneAxisEachWithTheSameSense) {
  auto t = openffboard_transport();
  HidPidJoystick joystick(*t, testing::shipped_openffboard(), testing::synchronous());
  // Create New Effect, feature 0x11 (ffb_defs.h:60, :197-199): type at byte 1, FFB_EFFECT_CONSTANT = 1 (ffb_defs.h:73).
  const auto created = outputs_with_id(*t, 0x11, Op::SetFeature);
  ASSERT_EQ(created.size(), 2u);
  for (const auto& c : created) EXPECT_EQ(c[1], 1);
  // FFB_SetEffect_t (ffb_defs.h:161-172), HID_ID_EFFREP 0x01.
  const auto effects = outputs_with_id(*t, 0x01);
  ASSERT_EQ(effects.size(), 2u);
  for (std::size_t a = 0; a < 2; ++a) {
    SCOPED_TRACE(a);
    const Bytes& e = effects[a];
    ASSERT_GE(e.size(), 18u);  // the firmware copies min(sizeof(FFB_SetEffect_t) = 18, size) (HidFFB.cpp:93)
    EXPECT_EQ(e[1], a + 1);                   // effectBlockIndex (:162)
    EXPECT_EQ(e[2], 1);                       // effectType: constant (:163)
    EXPECT_EQ(u16(e, 3), 0xFFFF);             // duration: infinite (:164; HidFFB.cpp:324-328)
    EXPECT_EQ(u16(e, 9), 0);                  // startDelay (:167)
    EXPECT_EQ(e[11], 255);                    // gain: x 255/255 (:168)
    EXPECT_EQ(e[13] & 0x04, 0x04);            // Direction Enable: one polar direction (:170), as hid-pidff sends
    EXPECT_EQ(e[13] & 0x03, 1 << a);          // enableAxis: this axis (ignored under Direction Enable)
    EXPECT_EQ(u16(e, 14), a == 0 ? 9000 : 18000);  // directionX: 90 degrees for X, 180 for Y (:171)
  }
  // The firmware's factor for each effect's own axis (HidFFB.cpp:320-321): +1 on both axes, so one
  // sign convention holds for X and Y; the other axis gets 0.
  EXPECT_NEAR(axis_factor(effects[0], 0), 1.0, 1e-12);
  EXPECT_NEAR(axis_factor(effects[0], 1), 0.0, 1e-12);
  EXPECT_NEAR(axis_factor(effects[1], 1), 1.0, 1e-12);
  EXPECT_NEAR(axis_factor(effects[1], 0), 0.0, 1e-12);
  // FFB_EffOp_Data_t (ffb_defs.h:264-267), HID_ID_EFOPREP 0x0A: state 1 = start (HidFFB.cpp:389-413).
  const auto ops = outputs_with_id(*t, 0x0A);
  ASSERT_GE(ops.size(), 2u);
  EXPECT_EQ(ops[0][1], 1);
  EXPECT_EQ(ops[0][2], 1);
  EXPECT_EQ(ops[1][1], 2);
  EXPECT_EQ(ops[1][2], 1);
}

TEST(OpenFFBoardFirmware, SetConstantForceCarriesTheSignedMagnitude) {
  auto t = openffboard_transport();
  HidPidJoystick joystick(*t, testing::shipped_openffboard(), testing::synchronous());
  t->clear_log();
  ASSERT_TRUE(joystick.write_force_rt({1.5, -2.25}));
  // FFB_SetConstantForce_Data_t (ffb_defs.h:302-304), HID_ID_CONSTREP 0x05: block index, int16
  // magnitude taken raw (HidFFB.cpp:228-234). 10 N over the Magnitude's 32767 (openffboard-2axis.toml,
  // uncalibrated): 1.5 N is 4915.05 units, 2.25 N 7372.575, rounded half away from zero; command_sense
  // -1: the firmware pushes the handle toward -x for a positive magnitude.
  const auto forces = outputs_with_id(*t, 0x05);
  ASSERT_EQ(forces.size(), 2u);
  EXPECT_EQ(forces[0][1], 1);
  EXPECT_EQ(i16(forces[0], 2), -4915);
  EXPECT_EQ(forces[1][1], 2);
  EXPECT_EQ(i16(forces[1], 2), 7373);
}

std::unique_ptr<FakeTransport> wheel_transport() {
  auto t = std::make_unique<FakeTransport>(
      testing::read_hex_file(std::filesystem::path(SANDPAPER_SOURCE_DIR) / "tests/runtime/usb/data/openffboard_1axis_wheel.hex"));
  t->add_feature_reply(0x13, {0x13, 0x00, 0x10, 40, 0x01});
  t->add_feature_reply(0x12, {0x12, 0x01, 0x01, 0x00, 0x10});
  t->add_input({UsbStatus::Ok, position_report(0, 0)});
  return t;
}

TEST(OpenFFBoardFirmware, TheOneAxisWheelIsRefusedAsAJoystick) {
  // hid_1ffb_desc: Set Effect's Axes Enable has X only, so a Y effect would do nothing.
  auto t = wheel_transport();
  try {
    HidPidJoystick joystick(*t, testing::shipped_openffboard(), testing::synchronous());
    ADD_FAILURE() << "the 1-axis wheel opened as a 2-axis joystick";
  } catch (const HidPidError& e) {
    EXPECT_NE(std::string(e.what()).find("usage 0x0031"), std::string::npos) << e.what();  // Y
    EXPECT_NE(std::string(e.what()).find("openffboard-wheel"), std::string::npos) << e.what();  // what to play it with
  }
  EXPECT_TRUE(t->kernel_driver_attached());  // given back
}

TEST(OpenFFBoardFirmware, TheWheelPlaysItsOneAxisWithItsOwnDeviceFile) {
  auto t = wheel_transport();
  const auto& wheel = testing::shipped_openffboard_wheel();
  ASSERT_TRUE(wheel.wheel());
  {
    HidPidJoystick joystick(*t, wheel, testing::synchronous());
    // One effect, on X alone: Create New Effect once, Set Effect with Axes Enable X.
    EXPECT_EQ(joystick.effect_block_index(0), 1);
    EXPECT_EQ(joystick.effect_block_index(1), 0);
    EXPECT_EQ(outputs_with_id(*t, 0x11, Op::SetFeature).size(), 1u);
    const auto effects = outputs_with_id(*t, 0x01);
    ASSERT_EQ(effects.size(), 1u);
    EXPECT_EQ(effects[0][1], 1);
    EXPECT_EQ(effects[0][13] & 0x01, 1);  // Axes Enable: X (the 1-axis Set Effect has no Y bit)
    // Position: X along the rim over the file's 2356.2 mm (900 deg of a 150 mm rim); the gamepad's
    // Y is not the wheel's and reads 0.
    glm::dvec2 p{1, 1};
    t->add_input({UsbStatus::Ok, position_report(16384, -32767)});
    ASSERT_TRUE(joystick.read_position_rt(0.0, p));
    EXPECT_NEAR(p.x, 16384.0 / 32767.0 * 2.3562 / 2, 1e-6);
    EXPECT_EQ(p.y, 0.0);
    // A force: X's Set Constant Force only; what was asked of y is not sent.
    t->clear_log();
    ASSERT_TRUE(joystick.write_force_rt({1.5, -2.25}));
    const auto forces = outputs_with_id(*t, 0x05);
    ASSERT_EQ(forces.size(), 1u);
    EXPECT_EQ(forces[0][1], 1);
    EXPECT_EQ(i16(forces[0], 2), -4915);  // 1.5 N at 10 N / 32767, command_sense -1 (as the joystick's X)
    t->clear_log();
  }
  // Closed: one effect stopped and freed.
  EXPECT_EQ(outputs_with_id(*t, 0x0A).size(), 1u);
  EXPECT_TRUE(t->kernel_driver_attached());
}

}  // namespace
}  // namespace sandpaper::runtime::usb
