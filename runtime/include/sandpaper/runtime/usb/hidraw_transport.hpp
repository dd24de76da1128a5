#pragma once
// The UsbTransport on Linux's hidraw interface (Documentation/hid/hidraw.rst): output reports by
// write(), feature reports by HIDIOCSFEATURE and HIDIOCGFEATURE, input reports by read(). The
// kernel's HID driver stays bound (usbhid, and hid-pidff if it took the device), so the joystick
// stays a joystick for every other program and no root is needed beyond access to the node.
// Reports are passed as on the wire, as UsbTransport says; for a descriptor without report IDs the
// transport adds and removes hidraw's leading zero byte itself.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sandpaper/runtime/usb/transport.hpp"

namespace sandpaper::runtime::usb {

// One hidraw node and what the kernel says of its device. Units: none.
struct HidrawNode {
  std::string path;                 // "/dev/hidraw0"
  std::uint16_t vendor_id = 0, product_id = 0;
  bool usb = false;                 // bus type 3 (BUS_USB): otherwise Bluetooth, I2C, virtual ...
  std::string name;                 // HID_NAME, the device's own product name
  bool descriptor_read = false;     // its report descriptor was read (from sysfs, which needs no access)
  bool has_pid = false;             // ... and it has a Physical Interface Device (force-feedback) usage
  int force_axes = 0;               // the axes its effects act on (UsbHidDeviceInfo::force_axes)
  std::string descriptor_error;     // not empty: the descriptor was read and refused, in the parser's words
};

// Every hidraw node (/sys/class/hidraw), sorted by number. Never throws.
std::vector<HidrawNode> list_hidraw_nodes();

// The vendor and product of a sysfs uevent text's HID_ID line ("HID_ID=0003:00001209:0000FFB0"),
// and its HID_NAME; false if there is no well-formed HID_ID line.
bool parse_hid_uevent(const std::string& uevent, HidrawNode& node);

class HidrawTransport final : public UsbTransport {
 public:
  // Opens `path` for reading and writing. NoDevice if it is not there, AccessDenied without
  // permission (docs/DEVICES.md: the udev rule); `message` says more.
  static UsbStatus open(const std::string& path, std::unique_ptr<HidrawTransport>& out, std::string& message);
  ~HidrawTransport() override;

  UsbStatus report_descriptor(std::vector<std::uint8_t>& descriptor) override;
  // The kernel's driver is never taken: detaching and attaching do nothing, and succeed.
  UsbStatus detach_kernel_driver() override { return UsbStatus::Ok; }
  UsbStatus attach_kernel_driver() override { return UsbStatus::Ok; }
  UsbStatus claim_interface() override { return UsbStatus::Ok; }
  UsbStatus release_interface() override { return UsbStatus::Ok; }
  UsbStatus read_input(std::span<std::uint8_t> buffer, std::size_t& length, unsigned timeout_ms) noexcept override;
  UsbStatus write_output(std::span<const std::uint8_t> report) noexcept override;
  UsbStatus set_feature(std::span<const std::uint8_t> report) override;
  UsbStatus get_feature(std::uint8_t report_id, std::span<std::uint8_t> buffer, std::size_t& length) override;

  const std::string& path() const noexcept { return path_; }

 private:
  HidrawTransport() = default;
  // The status of a failed call's errno; an I/O error from a device that has gone is NoDevice.
  UsbStatus failed(int error) noexcept;
  int fd_ = -1;
  std::string path_;
  bool numbered_ = true;  // the descriptor uses report IDs (found when it is read)
};

}  // namespace sandpaper::runtime::usb
