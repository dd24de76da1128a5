// The OpenFFBoard firmware's second main class, the 1-axis wheel (FFBWheel with its 1-axis HID
// descriptor, usb_hid_1ffb_desc.c), compiled for the host beside the joystick and chosen as the
// board chooses it: by the flash's current config. A material on a wheel is felt along its one
// axis: the wheel drives one motor, and an effect asked of a second axis moves nothing. Cited lines
// are in ../shared/third_party/openffboard/Firmware/FFBoard at commit 160af91.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>

#include "firmware_driving.hpp"

namespace sandpaper::usb_lab {

OpenFFBoardFirmware& firmware() { return started_once(MainClass::Wheel); }

namespace {

// wDescriptorLength of the HID descriptor (HID 1.11 section 6.2.1) in the function's descriptors.
int report_descriptor_length(const Bytes& function) {
  for (std::size_t at = 0; at + 8 < function.size(); at += function[at])
    if (function[at + 1] == 0x21) return function[at + 7] | (function[at + 8] << 8);
  return -1;
}

TEST(OpenFFBoardWheelLab, IsTheOneAxisWheelWithItsOwnReportDescriptor) {
  EXPECT_EQ(firmware().axes(), 1);
  EXPECT_THROW(firmware().set_position(1, 0.0), std::out_of_range);
  // Its configuration carries the 1-axis report descriptor, not the joystick's 1215 bytes
  // (firmware_test.cpp), and GET_DESCRIPTOR returns that many bytes.
  const int length = report_descriptor_length(firmware().function_descriptors());
  ASSERT_GT(length, 0);
  EXPECT_LT(length, 1215);
  const ControlReply r = firmware().control(SetupPacket{0x81, 0x06, 0x2200, 0, 4096}, {});
  ASSERT_FALSE(r.stall);
  EXPECT_EQ(static_cast<int>(r.data.size()), length);
  // The same board: the IDs a calibration file matches (1209:FFB0, pid.codes' OpenFFBoard).
  EXPECT_EQ(firmware().identity().vendor_id, 0x1209);
  EXPECT_EQ(firmware().identity().product_id, 0xFFB0);
}

// tests/runtime/usb/data/openffboard_1axis_wheel.hex was expanded from the firmware at commit
// d19d616 (the descriptor Sandpaper's parser tests read as one force axis); the firmware built here
// (160af91) differs from it in the bytes firmware_test.cpp explains for the 2-axis file: the twelve
// vendor command fields (same offsets) and Set Constant Force's Magnitude minimum (-32767), which
// sits 19 bytes earlier here because the 1-axis Set Effect report is shorter.
constexpr DescriptorChange newer_wheel_firmware_changes[] = {
    {78, 0x02, 0x01},  {86, 0x02, 0x01},  {94, 0x02, 0x01},  {102, 0x02, 0x01}, {110, 0x02, 0x01},
    {118, 0x02, 0x01}, {133, 0x02, 0x01}, {141, 0x02, 0x01}, {149, 0x02, 0x01}, {157, 0x02, 0x01},
    {165, 0x02, 0x01}, {173, 0x02, 0x01}, {779, 0x00, 0x01}, {785, 0x00, 0x01},
};

TEST(OpenFFBoardWheelLab, ReportDescriptorIsTheRecordedWheels) {
  // USB_HID_1FFB_REPORT_DESC_SIZE (usb_hid_ffb_desc.h:753)
  expect_report_descriptor("openffboard_1axis_wheel.hex", 1196, newer_wheel_firmware_changes);
}

TEST(OpenFFBoardWheelLab, AConstantForceTurnsTheWheelsOneMotor) {
  const OpenDevice d = open_like_the_driver();
  ASSERT_TRUE(always([](const FirmwareState& s) { return s.torque[0] == 0; }, milliseconds(20)));
  constant_force(d.x_block, 10000);
  EXPECT_TRUE(eventually([](const FirmwareState& s) { return s.torque[0] > 0; }, kSettle));
  constant_force(d.x_block, -10000);
  EXPECT_TRUE(eventually([](const FirmwareState& s) { return s.torque[0] < 0; }, kSettle));
  constant_force(d.x_block, 0);
  EXPECT_TRUE(eventually([](const FirmwareState& s) { return s.torque[0] == 0; }, kSettle));
  // No second motor was ever driven.
  EXPECT_EQ(firmware().state().torque_updates[1], 0u);
}

TEST(OpenFFBoardWheelLab, AnEffectOnASecondAxisMovesNothing) {
  const OpenDevice d = open_like_the_driver();
  const std::uint8_t y = open_constant_force_effect(1);  // as a 2-axis driver would ask
  constant_force(y, 10000);
  EXPECT_TRUE(always([](const FirmwareState& s) { return s.torque[0] == 0 && s.torque_updates[1] == 0; },
                     milliseconds(100)));
  constant_force(y, 0);
  constant_force(d.x_block, 0);
}

}  // namespace
}  // namespace sandpaper::usb_lab
