// The evdev entry of the device factory: a force-feedback device the kernel drives (usbhid with
// hid-pidff, or a vendor driver), played through its input event node (docs/DEVICES.md). Nothing is
// taken from the kernel: the joystick stays a joystick for every other program while Sandpaper plays.
#include "devices_internal.hpp"
#include "sandpaper/runtime/evdev/evdev_joystick.hpp"
#include "sandpaper/runtime/usb/libusb_transport.hpp"

#include <cerrno>
#include <fstream>
#include <iterator>
#include <vector>

namespace sandpaper::runtime {

using Cause = DeviceOpenError::Cause;
using calibration::DeviceCalibration;

int force_axes_of(const evdev::EvdevNode& node) {
  if (node.report_descriptor.empty()) return 0;
  std::ifstream in(node.report_descriptor, std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  usb::UsbHidDeviceInfo info;
  usb::summarise_report_descriptor(bytes, info);
  return info.force_axes;
}

namespace {

struct EvdevChoice {
  evdev::EvdevNode node;
  const DeviceCalibration* calibration = nullptr;
};

// The node's own calibration file; else, when the user accepted it (--uncalibrated), the profile.
const DeviceCalibration* calibration_of(const calibration::CalibrationSet& set, const DeviceSpec& spec, const evdev::EvdevNode& node) {
  if (const DeviceCalibration* own = usb_calibration_of(set, node.usb(), node.vendor_id, node.product_id, force_axes_of(node)))
    return own;
  return spec.uncalibrated ? set.find_device(evdev::kUncalibratedProfile) : nullptr;
}

const char* const kUncalibratedHelp =
    "play it with --uncalibrated (the uncalibrated-evdev profile: at most a quarter of its strongest force, newtons and "
    "directions assumed), or measure it and write its calibration file (docs/CALIBRATION.md)";

// "evdev" or "evdev:PATH", from `device` itself or, once resolved to a calibration, `through`.
std::string evdev_request(const DeviceSpec& spec) {
  if (is_evdev_device(spec.device)) return spec.device;
  return is_evdev_device(spec.through) ? spec.through : std::string();
}

std::string describe(const evdev::EvdevNode& n) {
  return (n.name.empty() ? std::string("an input device") : "'" + n.name + "'") + " (" + usb_ids(n.vendor_id, n.product_id) + ")";
}

EvdevChoice choose_evdev(const calibration::CalibrationSet& set, const DeviceSpec& spec, const DeviceCalibration* cal) {
  const std::string request = evdev_request(spec);
  const std::string wanted = request.size() > 6 ? request.substr(6) : std::string();  // "evdev:/dev/input/event3"
  const auto nodes = evdev::list_force_feedback_nodes();
  const std::string known = "known devices: " + known_usb_devices(set);
  if (spec.uncalibrated && set.find_device(evdev::kUncalibratedProfile) == nullptr)
    throw DeviceOpenError(Cause::NoCalibration, std::string("--uncalibrated plays with the profile ") + evdev::kUncalibratedProfile +
                                                    ", which " + set.directory().string() + "/profiles/ lacks");
  if (!wanted.empty()) {
    const evdev::EvdevNode* n = evdev::find_node(nodes, wanted);
    if (n == nullptr)
      throw DeviceOpenError(Cause::NoUsb, "no input event node with force feedback at " + wanted + " (" +
                                              std::to_string(nodes.size()) + " such node(s) in /sys/class/input)");
    const DeviceCalibration* found = calibration_of(set, spec, *n);
    if (found == nullptr)
      throw DeviceOpenError(Cause::NoCalibration, wanted + " is " + describe(*n) +
                                                      ", which no device calibration with a [usb] table names: " + kUncalibratedHelp +
                                                      "\n  " + known);
    if (cal != nullptr && found != cal)
      throw DeviceOpenError(Cause::NoCalibration, wanted + " is " + describe(*n) + ", which is not " + cal->name +
                                                      " (docs/CALIBRATION.md)\n  " + known);
    return {*n, found};
  }
  // A device with its own file first, with or without --uncalibrated.
  for (const auto& n : nodes)
    if (const DeviceCalibration* own = usb_calibration_of(set, n.usb(), n.vendor_id, n.product_id, force_axes_of(n));
        own != nullptr && (cal == nullptr || own == cal))
      return {n, own};
  for (const auto& n : nodes)
    if (const DeviceCalibration* found = calibration_of(set, spec, n); found != nullptr && (cal == nullptr || found == cal))
      return {n, found};
  if (!nodes.empty())
    throw DeviceOpenError(Cause::NoCalibration, "force-feedback input devices are present (" + describe(nodes.front()) +
                                                    (nodes.size() > 1 ? ", ..." : "") + ") but none has a device calibration: " +
                                                    kUncalibratedHelp + "\n  " + known);
  throw DeviceOpenError(Cause::NoUsb, "no input event node with force feedback (/sys/class/input)\n  " + known);
}

}  // namespace

bool is_evdev_device(const std::string& device) { return device == "evdev" || device.rfind("evdev:", 0) == 0; }

bool serves_evdev(const DeviceSpec& spec, const DeviceCalibration*) { return !evdev_request(spec).empty(); }

std::string evdev_calibration(const calibration::CalibrationSet& set, const DeviceSpec& spec, const DeviceCalibration* cal) {
  refuse_simulated_hands(spec);
  return choose_evdev(set, spec, cal).calibration->name;
}

OpenedDevice open_evdev(const calibration::CalibrationSet& set, DeviceSpec& spec, const DeviceCalibration* cal) {
  refuse_simulated_hands(spec);
  const EvdevChoice choice = choose_evdev(set, spec, cal);
  const DeviceCalibration& found = *choice.calibration;
  const auto& node = choice.node;
  const std::string ids = usb_ids(node.vendor_id, node.product_id);
  OpenedDevice out;
  try {
    auto joystick = std::make_unique<evdev::EvdevJoystick>(node, found);
    out.held = joystick.get();
    out.device = std::move(joystick);
  } catch (const evdev::EvdevError& e) {
    const bool denied = e.error == EACCES || e.error == EPERM;
    throw DeviceOpenError(denied ? Cause::AccessDenied : e.error == ENOENT || e.error == ENODEV ? Cause::NoUsb : Cause::Refused,
                          "cannot play on " + node.path + " (" + found.name + ", " + ids + "): " + e.what(),
                          denied ? "  permission to open " + node.path + " is missing; the .deb's udev rules give force-feedback "
                                   "event devices to the person at the seat (`sandpaper devices --udev-rules`); add them to "
                                   "/etc/udev/rules.d/70-sandpaper.rules, run `sudo udevadm control --reload` and replug\n"
                                 : "");
  }
  out.calibration = found.name;
  out.description = found.name + " (" + ids + ") through " + node.path + ", the kernel's force feedback" +
                    (found.name == evdev::kUncalibratedProfile ? std::string(", no calibration file: assumed scale, a quarter of its force") : "");
  set_node(out, node.vendor_id, node.product_id, node.name, node.path, "evdev");
  return out;
}

}  // namespace sandpaper::runtime
