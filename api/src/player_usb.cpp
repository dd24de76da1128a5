// sandpaper::Player::usb: the first calibrated USB HID PID joystick plugged in (docs/USB_PID.md).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/runtime/usb/owned_joystick.hpp"
#include "sandpaper/sandpaper.hpp"

namespace sandpaper {
namespace {

using runtime::usb::UsbStatus;

std::string hex4(int v) {
  char s[8];
  std::snprintf(s, sizeof s, "%04x", static_cast<unsigned>(v) & 0xFFFFu);
  return s;
}

std::string ids(int vendor, int product) { return hex4(vendor) + ":" + hex4(product); }

std::string udev_help(int vendor, int product) {
  return "; permission to open it is missing: add SUBSYSTEM==\"usb\", ATTR{idVendor}==\"" + hex4(vendor) +
         "\", ATTR{idProduct}==\"" + hex4(product) +
         "\", MODE=\"0660\", TAG+=\"uaccess\" to /etc/udev/rules.d/70-sandpaper.rules, run "
         "`sudo udevadm control --reload` and replug it";
}

}  // namespace

Player Player::usb(const Library& library) { return usb(library.compiler().calibration()); }

Player Player::usb(const calibration::CalibrationSet& set) {
  std::string known;
  for (const auto& d : set.devices())
    if (d.usb_vendor_id >= 0) known += (known.empty() ? "" : ", ") + d.name + " (" + ids(d.usb_vendor_id, d.usb_product_id) + ")";
  if (known.empty()) known = "none";
  const auto found = runtime::usb::list_usb_hid_devices();
  if (found.status != UsbStatus::Ok)
    throw DeviceError("cannot search USB for a force-feedback joystick: " + found.message +
                      "; joysticks the calibration knows: " + known);
  for (const auto& info : found.devices) {
    for (const auto& cal : set.devices()) {
      if (cal.usb_vendor_id != info.vendor_id || cal.usb_product_id != info.product_id) continue;
      const std::string which = ids(info.vendor_id, info.product_id) + " (" + cal.name + ")";
      std::unique_ptr<runtime::usb::LibusbTransport> transport;
      std::string message;
      const UsbStatus s = runtime::usb::LibusbTransport::open(static_cast<std::uint16_t>(info.vendor_id),
                                                              static_cast<std::uint16_t>(info.product_id), transport, message);
      if (s != UsbStatus::Ok)
        throw DeviceError("cannot open " + which + ": " + message +
                          (s == UsbStatus::AccessDenied ? udev_help(info.vendor_id, info.product_id) : ""));
      try {
        Player p(std::make_unique<runtime::usb::OwnedHidPidJoystick>(std::move(transport), cal));
        p.set_device_calibration_nonrt(cal.name);
        return p;
      } catch (const runtime::usb::HidPidError& e) {
        throw DeviceError("cannot play on " + which + ": " + e.what() +
                          (e.status == UsbStatus::AccessDenied ? udev_help(info.vendor_id, info.product_id) : ""));
      }
    }
  }
  std::error_code ec;
  throw DeviceError("no USB force-feedback joystick that the calibration knows is plugged in (" +
                    std::to_string(found.devices.size()) + " USB HID device(s) checked); joysticks it knows: " + known +
                    (std::filesystem::exists("/dev/bus/usb", ec) ? ""
                                                                  : "; this system shows no USB bus (/dev/bus/usb is missing: a "
                                                                    "container or VM without USB passthrough?)"));
}

}  // namespace sandpaper
