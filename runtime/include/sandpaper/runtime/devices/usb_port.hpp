#pragma once
// Where a USB device sits on the bus, read from Linux's sysfs, so a fault can be named: a device
// that leaves the bus and comes back at the same port under a new address was reset (a firmware
// that rebooted, a hub that re-enumerated it); one that stays away was unplugged.
// The kernel names each USB device's folder in /sys/bus/usb/devices by its port path
// ("1-1", "3-2.4": bus, then hub ports; Linux drivers/usb/core/usb.c) and gives each new
// enumeration the next free address (devnum), so the same name with a new devnum is the same port
// enumerated again.
#include <cstdint>
#include <optional>
#include <string>

namespace sandpaper::runtime {

struct UsbPort {
  std::string name;  // the port path, the folder's name under /sys/bus/usb/devices ("1-1")
  int devnum = 0;    // the device's address on its bus when read (1-127)
  std::uint16_t vendor_id = 0, product_id = 0;
};

// Whether `name` is a USB device's port path: digits, '-', digits, then any ".digits"
// ("1-1", "3-2.4"); not a root hub ("usb1") nor an interface ("1-1:1.0").
bool usb_port_name(const std::string& name) noexcept;
// A decimal sysfs attribute ("3", "3\n") as a number in 1..127 (a USB address), or 0.
int usb_address_text(const std::string& text) noexcept;

// The USB device a sysfs folder belongs to: the folder or its nearest parent named like a port
// that holds devnum, idVendor and idProduct. nullopt when there is none (not a USB device).
std::optional<UsbPort> usb_port_of_sysfs(const std::string& sysfs_path);
// The USB device at `bus`, `address` (as libusb reports them), found in sysfs_root's bus/usb/devices.
std::optional<UsbPort> usb_port_of_address(int bus, int address, const std::string& sysfs_root = "/sys");
// The USB device a hidraw node ("/dev/hidraw0") or an input event node ("/dev/input/event3") hangs from.
std::optional<UsbPort> usb_port_of_node(const std::string& node, const std::string& sysfs_root = "/sys");

// Whether, within `grace_s` seconds, a device with the same IDs is at `port`'s port path under another
// address: the device was reset, not unplugged. Polls sysfs every 20 ms; returns as soon as it is back.
bool came_back_nonrt(const UsbPort& port, double grace_s, const std::string& sysfs_root = "/sys");

}  // namespace sandpaper::runtime
