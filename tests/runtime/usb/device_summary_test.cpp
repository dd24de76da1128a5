// What `sandpaper devices` learns from a device's report descriptor (summarise_report_descriptor):
// a descriptor the parser refuses keeps the parser's reason, so a device that will not open says why.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "sandpaper/runtime/usb/libusb_transport.hpp"
#include "usb_test_support.hpp"

namespace sandpaper::runtime::usb {
namespace {

TEST(DeviceSummary, APidJoystickIsReadWithItsPidUsage) {
  UsbHidDeviceInfo info;
  summarise_report_descriptor(testing::test_descriptor(), info);
  EXPECT_TRUE(info.descriptor_read);
  EXPECT_TRUE(info.has_pid);
  EXPECT_EQ(info.descriptor_error, "");
}

TEST(DeviceSummary, AGamepadWithoutPidIsReadWithout) {
  // Generic Desktop, Game Pad, Application collection: X, 8 bits, Input; End Collection.
  const std::vector<std::uint8_t> pad = {0x05, 0x01, 0x09, 0x05, 0xA1, 0x01, 0x09, 0x30, 0x75,
                                         0x08, 0x95, 0x01, 0x81, 0x02, 0xC0};
  UsbHidDeviceInfo info;
  summarise_report_descriptor(pad, info);
  EXPECT_TRUE(info.descriptor_read);
  EXPECT_FALSE(info.has_pid);
  EXPECT_EQ(info.descriptor_error, "");
}

TEST(DeviceSummary, ARefusedDescriptorKeepsTheParsersReasonAndNothingFromBefore) {
  UsbHidDeviceInfo info;
  summarise_report_descriptor(testing::test_descriptor(), info);
  // F22's nine bytes: 1-bit fields, Report Count 0xFFFFFFFF, Input.
  const std::vector<std::uint8_t> four_billion = {0x75, 0x01, 0x97, 0xFF, 0xFF, 0xFF, 0xFF, 0x81, 0x02};
  summarise_report_descriptor(four_billion, info);
  EXPECT_FALSE(info.descriptor_read);
  EXPECT_FALSE(info.has_pid);
  EXPECT_NE(info.descriptor_error.find("Report Count 4294967295 is over 12288"), std::string::npos) << info.descriptor_error;
}

}  // namespace
}  // namespace sandpaper::runtime::usb
