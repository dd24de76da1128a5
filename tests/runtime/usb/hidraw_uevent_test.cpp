// What the hidraw family reads of a node's device from sysfs (parse_hid_uevent): the bus, vendor
// and product of its HID_ID line (Linux drivers/hid/hid-core.c, hid_uevent: "HID_ID=%04X:%08X:%08X").
#include <gtest/gtest.h>

#include <string>

#include "sandpaper/runtime/usb/hidraw_transport.hpp"

namespace sandpaper::runtime::usb {
namespace {

TEST(HidrawUevent, TheOpenFFBoardsLineGivesItsUsbIds) {
  HidrawNode node;
  ASSERT_TRUE(parse_hid_uevent("DRIVER=hid-generic\nHID_ID=0003:00001209:0000FFB0\nHID_NAME=Open FFBoard FFBoard\n"
                               "HID_PHYS=usb-dummy_hcd.0-1/input0\nMODALIAS=hid:b0003g0001v00001209p0000FFB0\n",
                               node));
  EXPECT_TRUE(node.usb);
  EXPECT_EQ(node.vendor_id, 0x1209);
  EXPECT_EQ(node.product_id, 0xFFB0);
  EXPECT_EQ(node.name, "Open FFBoard FFBoard");
}

TEST(HidrawUevent, ABluetoothDeviceIsNotUsb) {
  HidrawNode node;
  ASSERT_TRUE(parse_hid_uevent("HID_ID=0005:0000045E:000002E0\n", node));
  EXPECT_FALSE(node.usb);
  EXPECT_EQ(node.vendor_id, 0x045E);
}

TEST(HidrawUevent, NoWellFormedIdLineIsNoDevice) {
  for (const std::string text : {"", "HID_NAME=x\n", "HID_ID=0003:1209\n", "HID_ID=0003:00011209:0000FFB0\n",
                                 "HID_ID=zz03:00001209:0000FFB0\n"}) {
    HidrawNode node;
    EXPECT_FALSE(parse_hid_uevent(text, node)) << text;
  }
}

}  // namespace
}  // namespace sandpaper::runtime::usb
