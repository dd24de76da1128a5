// `sandpaper devices` and `sandpaper run --device usb`: USB HID PID force-feedback joysticks
// (docs/USB_PID.md). The devices the runtime knows are the calibrations with a [usb] table.
#include <filesystem>
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "cli.hpp"
#include "sandpaper/player/play.hpp"
#include "sandpaper/player/usb_devices.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/usb/owned_joystick.hpp"
#include "sandpaper/runtime/usb/libusb_transport.hpp"

namespace sandpaper::cli {

using runtime::usb::UsbStatus;

namespace {
// A refused descriptor is named with the parser's reason: such a device cannot be opened, and "not
// read" would send its owner looking at permissions.
std::string descriptor_summary(const runtime::usb::UsbHidDeviceInfo& info) {
  if (info.descriptor_read) return info.has_pid ? "HID PID force feedback" : "no PID usage in its descriptor";
  if (!info.descriptor_error.empty()) return "report descriptor refused (" + info.descriptor_error + ")";
  return "descriptor not read";
}
}  // namespace

int cmd_devices(const CommonOptions& o) {
  CommonOptions base = o;
  base.device = "sim";
  const auto c = make_compiler(base);
  std::vector<Found> found;
  if (!find_devices(c.calibration(), found, "devices")) return kExitUsage;
  bool denied = false;
  for (const auto& f : found) {
    std::cout << fmt::format("{} bus {} address {}{}: {}; {}\n", ids(f.info.vendor_id, f.info.product_id), f.info.bus,
                             f.info.address, f.info.product.empty() ? "" : " \"" + f.info.product + "\"",
                             descriptor_summary(f.info),
                             f.calibration ? "calibration " + f.calibration->name + " (" + f.calibration->file + ")"
                                           : std::string("no device calibration: cannot be played yet"));
    if (f.info.open_status == UsbStatus::AccessDenied) {
      denied = true;
      print_udev_help(std::cout, f.info.vendor_id, f.info.product_id);
    }
  }
  return denied ? kExitUsage : kExitOk;
}

std::unique_ptr<runtime::Device> open_usb_joystick(const CommonOptions& o, std::string& device_name, std::string& error,
                                                   double watchdog_ms) {
  CommonOptions base = o;
  base.device = "sim";
  const auto probe = make_compiler(base);
  std::vector<Found> found;
  if (!find_devices(probe.calibration(), found, "studio --device usb")) {
    error = "no USB force-feedback joystick found";
    return nullptr;
  }
  for (const auto& f : found) {
    if (!f.calibration) continue;
    std::unique_ptr<runtime::usb::LibusbTransport> transport;
    std::string message;
    const UsbStatus st = runtime::usb::LibusbTransport::open(static_cast<std::uint16_t>(f.info.vendor_id),
                                                             static_cast<std::uint16_t>(f.info.product_id), transport, message);
    if (st != UsbStatus::Ok) {
      error = "cannot open " + ids(f.info.vendor_id, f.info.product_id) + ": " + message;
      if (st == UsbStatus::AccessDenied) print_udev_help(std::cerr, f.info.vendor_id, f.info.product_id);
      return nullptr;
    }
    try {
      device_name = f.calibration->name;
      // The calibration lives in `probe`, which goes out of scope: the joystick keeps what it needs
      // of it (limits, command scale) at construction.
      runtime::usb::HidPidOptions options;
      options.stale_limit_s = watchdog_ms * 1e-3;
      return std::make_unique<runtime::usb::OwnedHidPidJoystick>(std::move(transport), *f.calibration, options);
    } catch (const runtime::usb::HidPidError& e) {
      error = e.what();
      return nullptr;
    }
  }
  error = "force-feedback devices are present but none has a device calibration with a [usb] table (docs/CALIBRATION.md)";
  return nullptr;
}

}  // namespace sandpaper::cli
