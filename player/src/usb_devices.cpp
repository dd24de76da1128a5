#include "sandpaper/player/usb_devices.hpp"

#include <filesystem>
#include <iostream>

#include <fmt/format.h>

namespace sandpaper::cli {

using runtime::usb::UsbStatus;

std::string ids(int vendor, int product) { return fmt::format("{:04x}:{:04x}", vendor, product); }

static std::string udev_rule(int vendor, int product) {
  return fmt::format("SUBSYSTEM==\"usb\", ATTR{{idVendor}}==\"{:04x}\", ATTR{{idProduct}}==\"{:04x}\", MODE=\"0660\", TAG+=\"uaccess\"",
                     vendor, product);
}

void print_udev_help(std::ostream& out, int vendor, int product) {
  out << "  permission to open the device is missing; add this line to /etc/udev/rules.d/70-sandpaper.rules:\n"
      << "    " << udev_rule(vendor, product) << "\n"
      << "  then run `sudo udevadm control --reload` and unplug and replug the device\n";
}

std::string known_list(const calibration::CalibrationSet& set) {
  std::string s;
  for (const auto& d : set.devices())
    if (d.usb_vendor_id >= 0) s += (s.empty() ? "" : ", ") + d.name + " (" + ids(d.usb_vendor_id, d.usb_product_id) + ")";
  return s.empty() ? "none" : s;
}

// Force-feedback devices present: a PID usage in the report descriptor, or a known VID:PID.
// Returns false (after printing why on stderr) when USB cannot be searched or none is present.
bool find_devices(const calibration::CalibrationSet& set, std::vector<Found>& found, const char* command) {
  const auto e = runtime::usb::list_usb_hid_devices();
  if (e.status != UsbStatus::Ok) {
    std::cerr << "sandpaper " << command << ": no USB force-feedback device: " << e.message
              << "\n  known devices: " << known_list(set) << "\n";
    return false;
  }
  for (const auto& info : e.devices) {
    const calibration::DeviceCalibration* cal = nullptr;
    for (const auto& d : set.devices())
      if (d.usb_vendor_id == info.vendor_id && d.usb_product_id == info.product_id) cal = &d;
    if (cal || info.has_pid) found.push_back({info, cal});
  }
  if (found.empty()) {
    std::cerr << "sandpaper " << command << ": no USB force-feedback device found (" << e.devices.size()
              << " USB HID device(s) checked, none with a Physical Interface Device usage or a known ID)"
              << (std::filesystem::exists("/dev/bus/usb") ? "" : "\n  this system shows no USB bus: /dev/bus/usb does not exist (a container or VM without USB passthrough?)")
              << "\n  known devices: " << known_list(set) << "\n";
    return false;
  }
  return true;
}

const Found* first_calibrated(const std::vector<Found>& found, const char* command) {
  for (const auto& f : found)
    if (f.calibration) return &f;
  std::cerr << "sandpaper " << command << ": force-feedback devices are present but none has a device calibration with a [usb] table "
               "(docs/CALIBRATION.md)\n";
  return nullptr;
}

}  // namespace sandpaper::cli
