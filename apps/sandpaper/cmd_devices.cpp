// `sandpaper devices`: the USB HID PID force-feedback joysticks plugged in (docs/USB_PID.md), each
// with the device calibration that knows its VID:PID, as the device factory would match them, and
// the paths it can be played through (docs/DEVICES.md).
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "cli.hpp"
#include "sandpaper/runtime/devices/open_device.hpp"
#include "sandpaper/runtime/evdev/evdev_node.hpp"
#include "sandpaper/runtime/usb/hidraw_transport.hpp"

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

// What the kernel's force feedback offers on an event node, for the listing; a wheel's device file
// (`cal`) plays its one axis though the node has more.
std::string evdev_summary(const runtime::evdev::EvdevNode& n, const calibration::DeviceCalibration* cal = nullptr) {
  if (!n.constant_force) return "no constant-force effect (FF_CONSTANT): cannot be played";
  if (n.axes == 0) return "no ABS_X or ABS_WHEEL axis: cannot be played";
  const bool wheel = cal != nullptr && cal->wheel();
  const int axes = wheel ? 1 : n.axes;
  return fmt::format("the kernel's force feedback, {} {}{}{}", axes, axes == 1 ? "axis" : "axes",
                     wheel ? " (a wheel: ABS_X along its rim)" : "",
                     n.report_descriptor.empty() ? "; not a HID device: a calibration file for it counts FF_CONSTANT levels" : "");
}
// A device no calibration file names plays only through a usable event node, and only when asked.
bool playable_uncalibrated(const runtime::evdev::EvdevNode& n) { return n.constant_force && n.axes > 0; }
constexpr const char* kUncalibrated = "no device calibration: uncalibrated, plays only with --uncalibrated (docs/DEVICES.md)";
constexpr const char* kUnplayable = "no device calibration: cannot be played yet";
}  // namespace

int cmd_devices(const CommonOptions& o) {
  CommonOptions base = o;
  base.device = "sim";
  const auto c = make_compiler(base);
  const runtime::UsbSearch search = runtime::find_usb_devices(c.calibration());
  const std::string known = "known devices: " + runtime::known_usb_devices(c.calibration());
  if (!search.searched) {
    std::cerr << "sandpaper devices: no USB force-feedback device: " << search.message << "\n  " << known << "\n";
    return kExitUsage;
  }
  if (search.found.empty()) {
    const std::string bus = runtime::no_usb_bus_note();
    std::cerr << "sandpaper devices: no USB force-feedback device found (" << search.hid_devices
              << " USB HID device(s) checked, none with a Physical Interface Device usage or a known ID)"
              << (bus.empty() ? "" : "\n  " + bus) << "\n  " << known << "\n";
    return kExitUsage;
  }
  bool denied = false;
  const auto hidraw = runtime::usb::list_hidraw_nodes();
  const auto events = runtime::evdev::list_force_feedback_nodes();
  for (const auto& f : search.found) {
    bool evdev_playable = false;
    for (const auto& n : events)
      evdev_playable = evdev_playable || (n.usb() && n.vendor_id == f.info.vendor_id && n.product_id == f.info.product_id &&
                                          playable_uncalibrated(n));
    std::cout << fmt::format("{} bus {} address {}{}: {}; {}\n", runtime::usb_ids(f.info.vendor_id, f.info.product_id),
                             f.info.bus, f.info.address, f.info.product.empty() ? "" : " \"" + f.info.product + "\"",
                             descriptor_summary(f.info),
                             f.calibration ? "calibration " + f.calibration->name + " (" + f.calibration->file + ")"
                                           : std::string(evdev_playable ? kUncalibrated : kUnplayable));
    const bool usb_denied = f.info.open_status == UsbStatus::AccessDenied;
    std::cout << "  through libusb: --device usb (usbhid detached while it plays)\n";
    bool hidraw_usable = false, hidraw_denied = false;
    for (const auto& n : hidraw)
      if (n.usb && n.vendor_id == f.info.vendor_id && n.product_id == f.info.product_id) {
        const bool may = ::access(n.path.c_str(), R_OK | W_OK) == 0;
        (may ? hidraw_usable : hidraw_denied) = true;
        std::cout << "  through hidraw: --device hidraw:" << n.path << " (the kernel's driver stays bound)\n";
      }
    bool evdev_usable = false, evdev_denied = false;
    for (const auto& n : events)
      if (n.usb() && n.vendor_id == f.info.vendor_id && n.product_id == f.info.product_id) {
        const bool may = ::access(n.path.c_str(), R_OK | W_OK) == 0;
        (may ? evdev_usable : evdev_denied) = true;
        std::cout << "  through evdev: --device evdev:" << n.path << (f.calibration ? "" : " --uncalibrated") << " ("
                  << evdev_summary(n, f.calibration) << ")\n";
      }
    if (evdev_denied)
      std::cout << "  this user may not open its input event node; the .deb's rules give force-feedback event devices to "
                   "the person at the seat (`sandpaper devices --udev-rules`)\n";
    // A path this user may not take is named with the rule that allows it; only a device that no
    // path can reach makes the listing fail.
    if (usb_denied || hidraw_denied) {
      std::cout << "  this user may not play it through " << (usb_denied && hidraw_denied ? "libusb or hidraw" : usb_denied ? "libusb" : "hidraw")
                << "; the line(s) for /etc/udev/rules.d/70-sandpaper.rules (docs/DEVICES.md):\n";
      if (usb_denied) std::cout << "    " << runtime::udev_rule(f.info.vendor_id, f.info.product_id) << "\n";
      if (hidraw_denied) std::cout << "    " << runtime::hidraw_udev_rule(f.info.vendor_id, f.info.product_id) << "\n";
      std::cout << "  then run `sudo udevadm control --reload` and unplug and replug the device\n";
    }
    if (usb_denied && !hidraw_usable && !evdev_usable) denied = true;
  }
  // Force-feedback input devices that are not USB HID PID joysticks (a wheel with a vendor driver,
  // a device on Bluetooth): the kernel plays them, and only through evdev.
  for (const auto& n : events) {
    bool listed = false;
    for (const auto& f : search.found) listed = listed || (n.usb() && n.vendor_id == f.info.vendor_id && n.product_id == f.info.product_id);
    if (listed) continue;
    const bool playable = playable_uncalibrated(n);
    std::cout << fmt::format("{} \"{}\": {}; {}\n  through evdev: --device evdev:{}{}\n", runtime::usb_ids(n.vendor_id, n.product_id),
                             n.name, evdev_summary(n), playable ? kUncalibrated : kUnplayable, n.path,
                             playable ? " --uncalibrated" : "");
  }
  return denied ? kExitUsage : kExitOk;
}

int cmd_devices_udev_rules(const CommonOptions& o) {
  CommonOptions base = o;
  base.device = "sim";
  std::cout << runtime::udev_rules_file(make_compiler(base).calibration());
  return kExitOk;
}

std::optional<runtime::OpenedDevice> open_device_for(const CommonOptions& o, runtime::DeviceSpec spec,
                                                     const std::string& command) {
  try {
    runtime::OpenedDevice opened = runtime::open_device(load_calibration_set(o), std::move(spec));
    if (!opened.warning.empty()) std::cerr << "sandpaper " << command << ": warning: " << opened.warning << "\n";
    return opened;
  } catch (const runtime::DeviceOpenError& e) {
    std::cerr << "sandpaper " << command << ": " << e.what() << "\n" << e.help;
    return std::nullopt;
  }
}

}  // namespace sandpaper::cli
