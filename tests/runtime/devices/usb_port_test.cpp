// Where a USB device sits, read from a sysfs tree laid out as Linux 6.1 lays it out (a hidraw node
// and an input event node of one HID interface of the device at port 1-1, its root hub usb1), and
// the reset test that names a device gone and back (runtime/devices/usb_port.hpp).
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "sandpaper/runtime/devices/usb_port.hpp"

namespace sandpaper::runtime {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// /devices/pci0000:00/0000:00:01.2/usb1 (root hub, address 1) / 1-1 (1209:ffb0, address 3) /
// 1-1:1.0 (interface) / 0003:1209:FFB0.0001 (HID device) / hidraw/hidraw0 and input/input5/event3,
// with class/ and bus/usb/devices/ linking to them as the kernel does.
class FakeSysfs {
 public:
  FakeSysfs() : root_(fs::temp_directory_path() / ("sandpaper-usb-port-" + std::to_string(::getpid()))) {
    fs::remove_all(root_);
    const fs::path hub = root_ / "devices/pci0000:00/0000:00:01.2/usb1";
    device_ = hub / "1-1";
    const fs::path hid = device_ / "1-1:1.0/0003:1209:FFB0.0001";
    write(hub / "devnum", "1\n");
    write(hub / "idVendor", "1d6b\n");
    write(hub / "idProduct", "0002\n");
    write(device_ / "devnum", "3\n");
    write(device_ / "idVendor", "1209\n");
    write(device_ / "idProduct", "ffb0\n");
    write(device_ / "1-1:1.0/bInterfaceNumber", "00\n");
    write(hid / "uevent", "HID_ID=0003:00001209:0000FFB0\n");
    fs::create_directories(hid / "hidraw/hidraw0");
    fs::create_directories(hid / "input/input5/event3");
    fs::create_directories(root_ / "class/hidraw/hidraw0");
    fs::create_directory_symlink(hid, root_ / "class/hidraw/hidraw0/device");
    fs::create_directories(root_ / "class/input/event3");
    fs::create_directory_symlink(hid / "input/input5", root_ / "class/input/event3/device");
    fs::create_directories(root_ / "bus/usb/devices");
    fs::create_directory_symlink(hub, root_ / "bus/usb/devices/usb1");
    fs::create_directory_symlink(device_, root_ / "bus/usb/devices/1-1");
  }
  ~FakeSysfs() { fs::remove_all(root_); }
  std::string root() const { return root_.string(); }
  const fs::path& device() const { return device_; }

 private:
  fs::path root_, device_;
};

TEST(UsbPort, PortPathsAndAddressesAreReadAsTheKernelWritesThem) {
  for (const char* name : {"1-1", "3-2.4", "10-1.2.3", "2-14"}) EXPECT_TRUE(usb_port_name(name)) << name;
  for (const char* name : {"usb1", "1-1:1.0", "1-", "-1", "1-1.", "1--1", "1-1..2", "", "1-1234", "1.1-1", "1-1-1"})
    EXPECT_FALSE(usb_port_name(name)) << name;
  EXPECT_EQ(usb_address_text("3\n"), 3);
  EXPECT_EQ(usb_address_text("127"), 127);
  for (const char* text : {"128", "0", "x", "", "\n", "3 ", "-3", "0003"}) EXPECT_EQ(usb_address_text(text), 0) << text;
}

TEST(UsbPort, NodesAndAddressesLeadToTheirPortNotTheRootHub) {
  const FakeSysfs sys;
  for (const char* node : {"/dev/hidraw0", "/dev/input/event3"}) {
    const auto port = usb_port_of_node(node, sys.root());
    ASSERT_TRUE(port) << node;
    EXPECT_EQ(port->name, "1-1");
    EXPECT_EQ(port->devnum, 3);
    EXPECT_EQ(port->vendor_id, 0x1209);
    EXPECT_EQ(port->product_id, 0xffb0);
  }
  EXPECT_FALSE(usb_port_of_node("/dev/hidraw1", sys.root()));  // no such node
  EXPECT_FALSE(usb_port_of_node("/dev/ttyS0", sys.root()));    // not a node the families open
  const auto by_address = usb_port_of_address(1, 3, sys.root());
  ASSERT_TRUE(by_address);
  EXPECT_EQ(by_address->name, "1-1");
  EXPECT_FALSE(usb_port_of_address(2, 3, sys.root()));  // the same address on another bus
  EXPECT_FALSE(usb_port_of_address(1, 4, sys.root()));
  // The root hub is a device at address 1, but not a port path: a node never resolves to it.
  EXPECT_FALSE(usb_port_of_address(1, 1, sys.root()));
}

TEST(UsbPort, OnlyTheSameDeviceUnderANewAddressIsAReset) {
  const FakeSysfs sys;
  const UsbPort port = *usb_port_of_node("/dev/hidraw0", sys.root());
  // Still at its old address (the kernel has not yet taken it away): not back.
  EXPECT_FALSE(came_back_nonrt(port, 0.05, sys.root()));
  write(sys.device() / "devnum", "4\n");
  EXPECT_TRUE(came_back_nonrt(port, 0.05, sys.root()));
  write(sys.device() / "idProduct", "ffb1\n");  // another device plugged into the same port
  EXPECT_FALSE(came_back_nonrt(port, 0.05, sys.root()));
  fs::remove(fs::path(sys.root()) / "bus/usb/devices/1-1");  // the port empty: unplugged
  EXPECT_FALSE(came_back_nonrt(port, 0.05, sys.root()));
}

}  // namespace
}  // namespace sandpaper::runtime
