// The USB entry of the device factory: find a force-feedback joystick through libusb, match it to a
// device calibration by VID:PID, open it with the HID PID driver (docs/USB_PID.md).
#include <cstdio>
#include <filesystem>

#include "devices_internal.hpp"
#include "sandpaper/runtime/usb/owned_joystick.hpp"

namespace sandpaper::runtime {

using Cause = DeviceOpenError::Cause;
using calibration::DeviceCalibration;
using usb::UsbStatus;

std::string usb_ids(int vendor, int product) {
  char s[16];
  std::snprintf(s, sizeof s, "%04x:%04x", static_cast<unsigned>(vendor) & 0xFFFFu, static_cast<unsigned>(product) & 0xFFFFu);
  return s;
}

std::string known_usb_devices(const calibration::CalibrationSet& set) {
  std::string s;
  for (const auto& d : set.devices())
    if (d.usb_vendor_id >= 0) s += (s.empty() ? "" : ", ") + d.name + " (" + usb_ids(d.usb_vendor_id, d.usb_product_id) + ")";
  return s.empty() ? "none" : s;
}

std::string udev_rule(int vendor, int product) {
  const std::string ids = usb_ids(vendor, product);
  return "SUBSYSTEM==\"usb\", ATTR{idVendor}==\"" + ids.substr(0, 4) + "\", ATTR{idProduct}==\"" + ids.substr(5) +
         "\", MODE=\"0660\", TAG+=\"uaccess\"";
}

std::string udev_help(int vendor, int product) {
  return "  permission to open the device is missing; add this line to /etc/udev/rules.d/70-sandpaper.rules:\n    " +
         udev_rule(vendor, product) + "\n  then run `sudo udevadm control --reload` and unplug and replug the device\n";
}

std::string no_usb_bus_note() {
  std::error_code ec;
  return std::filesystem::exists("/dev/bus/usb", ec)
             ? std::string()
             : "this system shows no USB bus: /dev/bus/usb does not exist (a container or VM without USB passthrough?)";
}

UsbSearch find_usb_devices(const calibration::CalibrationSet& set) {
  UsbSearch out;
  const auto e = usb::list_usb_hid_devices();
  if (e.status != UsbStatus::Ok) {
    out.message = e.message;
    return out;
  }
  out.searched = true;
  out.hid_devices = e.devices.size();
  for (const auto& info : e.devices) {
    const DeviceCalibration* cal = usb_calibration_of(set, true, info.vendor_id, info.product_id, info.force_axes);
    if (cal || info.has_pid) out.found.push_back({info, cal});
  }
  return out;
}

bool serves_usb(const DeviceSpec& spec, const DeviceCalibration* cal) {
  return spec.device == "usb" || (cal != nullptr && cal->usb_vendor_id >= 0 && !spec.simulate);
}

namespace {

// The first joystick plugged in whose calibration is known (`wanted`'s, when given); throws when none is.
UsbCandidate choose_usb(const calibration::CalibrationSet& set, const DeviceCalibration* wanted) {
  const std::string known = "known devices: " + known_usb_devices(set);
  const UsbSearch search = find_usb_devices(set);
  if (!search.searched) throw DeviceOpenError(Cause::NoUsb, "no USB force-feedback device: " + search.message + "\n  " + known);
  for (const auto& f : search.found)
    if (f.calibration && (wanted == nullptr || f.calibration->name == wanted->name)) return f;
  if (wanted != nullptr && !search.found.empty())
    throw DeviceOpenError(Cause::NoUsb, "no " + wanted->name + " (" + usb_ids(wanted->usb_vendor_id, wanted->usb_product_id) +
                                            ") is plugged in\n  " + known);
  if (!search.found.empty())
    throw DeviceOpenError(Cause::NoCalibration, "force-feedback devices are present but none has a device calibration "
                                                "with a [usb] table (docs/CALIBRATION.md)");
  const std::string bus = no_usb_bus_note();
  throw DeviceOpenError(Cause::NoUsb, "no USB force-feedback device found (" + std::to_string(search.hid_devices) +
                                          " USB HID device(s) checked, none with a Physical Interface Device usage or a "
                                          "known ID)" + (bus.empty() ? "" : "\n  " + bus) + "\n  " + known);
}


}  // namespace

void refuse_simulated_hands(const DeviceSpec& spec) {
  if (spec.virtual_clock)
    throw DeviceOpenError(Cause::WrongOptions, "--virtual-clock plays the simulated joystick; a USB joystick runs in real time");
  if (spec.hand == SimulatedHand::Replay || spec.hand == SimulatedHand::Dynamic)
    throw DeviceOpenError(Cause::WrongOptions,
                          "--replay and --hand-model move the simulated joystick; a USB joystick is moved by the hand holding it");
}

OpenedDevice open_hid_pid(std::unique_ptr<usb::UsbTransport> transport, const DeviceCalibration& cal, const DeviceSpec& spec,
                          const std::string& what, const std::string& access_help) {
  usb::HidPidOptions options;
  options.stale_limit_s = spec.watchdog_s;
  OpenedDevice out;
  try {
    auto joystick = std::make_unique<usb::OwnedHidPidJoystick>(std::move(transport), cal, options);
    out.usb_joystick = &joystick->joystick();
    out.held = joystick.get();
    out.device = std::move(joystick);
  } catch (const usb::HidPidError& e) {
    throw DeviceOpenError(e.status == UsbStatus::AccessDenied ? Cause::AccessDenied : Cause::Refused,
                          "cannot play on " + what + ": " + e.what(), e.status == UsbStatus::AccessDenied ? access_help : "");
  }
  out.calibration = cal.name;
  return out;
}

std::string usb_calibration(const calibration::CalibrationSet& set, const DeviceSpec& spec, const DeviceCalibration* wanted) {
  refuse_simulated_hands(spec);
  return choose_usb(set, wanted).calibration->name;
}

OpenedDevice open_usb(const calibration::CalibrationSet& set, DeviceSpec& spec, const DeviceCalibration* wanted) {
  refuse_simulated_hands(spec);
  const UsbCandidate candidate = choose_usb(set, wanted);
  const auto& info = candidate.info;
  const DeviceCalibration& cal = *candidate.calibration;
  const std::string ids = usb_ids(info.vendor_id, info.product_id);
  std::unique_ptr<usb::LibusbTransport> transport;
  std::string message;
  const UsbStatus opened = usb::LibusbTransport::open(info.vendor_id, info.product_id, transport, message);
  if (opened != UsbStatus::Ok)
    throw DeviceOpenError(opened == UsbStatus::AccessDenied ? Cause::AccessDenied : Cause::NoUsb,
                          "cannot open " + ids + " (" + cal.name + "): " + message,
                          opened == UsbStatus::AccessDenied ? udev_help(info.vendor_id, info.product_id) : "");
  OpenedDevice out = open_hid_pid(std::move(transport), cal, spec, ids + " (" + cal.name + ")",
                                  udev_help(info.vendor_id, info.product_id));
  out.description = cal.name + " (" + ids + ") on USB bus " + std::to_string(info.bus) + " address " + std::to_string(info.address);
  out.usb = info;
  out.transport = "libusb";
  return out;
}

}  // namespace sandpaper::runtime
