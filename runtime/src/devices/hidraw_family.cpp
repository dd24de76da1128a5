// The hidraw entry of the device factory: a HID PID joystick found among /dev/hidraw* and driven by
// the same HID PID driver as the libusb entry, through hidraw (docs/DEVICES.md). The kernel's driver
// stays bound, so the joystick stays a joystick for every other program while Sandpaper plays.
#include <filesystem>

#include "devices_internal.hpp"
#include "sandpaper/runtime/usb/hidraw_transport.hpp"

namespace sandpaper::runtime {

using Cause = DeviceOpenError::Cause;
using calibration::DeviceCalibration;
using usb::UsbStatus;

namespace {

struct HidrawChoice {
  usb::HidrawNode node;
  const DeviceCalibration* calibration = nullptr;
};

const DeviceCalibration* calibration_of(const calibration::CalibrationSet& set, const usb::HidrawNode& node) {
  return usb_calibration_of(set, node.usb, node.vendor_id, node.product_id, node.force_axes);
}

// "hidraw" or "hidraw:PATH", from `device` itself or, once resolved to a calibration, `through`.
std::string hidraw_request(const DeviceSpec& spec) {
  if (is_hidraw_device(spec.device)) return spec.device;
  return is_hidraw_device(spec.through) ? spec.through : std::string();
}

std::string hidraw_path(const std::string& request) {
  return request.size() > 7 ? request.substr(7) : std::string();  // "hidraw:/dev/hidraw3"
}

std::string canonical(const std::string& path) {
  std::error_code ec;
  const auto p = std::filesystem::canonical(path, ec);
  return ec ? path : p.string();
}

// The node `spec` names (hidraw:PATH), or the first whose device a calibration names (`cal`, when
// the spec names one).
HidrawChoice choose_hidraw(const calibration::CalibrationSet& set, const DeviceSpec& spec, const DeviceCalibration* cal) {
  const std::string known = "known devices: " + known_usb_devices(set);
  const std::string wanted = hidraw_path(hidraw_request(spec));
  const auto nodes = usb::list_hidraw_nodes();
  if (!wanted.empty()) {
    const std::string path = canonical(wanted);
    for (const auto& n : nodes)
      if (n.path == path) {
        const DeviceCalibration* found = calibration_of(set, n);
        if (found == nullptr || (cal != nullptr && found != cal))
          throw DeviceOpenError(Cause::NoCalibration, wanted + " is " + (n.name.empty() ? "a HID device" : "'" + n.name + "'") +
                                                          " (" + usb_ids(n.vendor_id, n.product_id) + "), which " +
                                                          (cal ? "is not " + cal->name : "no device calibration with a [usb] table names") +
                                                          "\n  " + known);
        return {n, found};
      }
    throw DeviceOpenError(Cause::NoUsb, "no hidraw node " + wanted + " (" + std::to_string(nodes.size()) +
                                            " hidraw node(s) in /sys/class/hidraw)");
  }
  bool force_feedback = false;
  for (const auto& n : nodes) {
    if (const DeviceCalibration* found = calibration_of(set, n); found != nullptr && (cal == nullptr || found == cal))
      return {n, found};
    force_feedback = force_feedback || n.has_pid;
  }
  if (force_feedback)
    throw DeviceOpenError(Cause::NoCalibration, "force-feedback devices have hidraw nodes but none has a device calibration "
                                                "with a [usb] table (docs/CALIBRATION.md)");
  throw DeviceOpenError(Cause::NoUsb, "no hidraw node of a known force-feedback device (" + std::to_string(nodes.size()) +
                                          " hidraw node(s) checked)\n  " + known);
}

}  // namespace

std::string hidraw_udev_rule(int vendor, int product) {
  const std::string ids = usb_ids(vendor, product);
  return "KERNEL==\"hidraw*\", ATTRS{idVendor}==\"" + ids.substr(0, 4) + "\", ATTRS{idProduct}==\"" + ids.substr(5) +
         "\", TAG+=\"uaccess\"";
}

const DeviceCalibration* usb_calibration_of(const calibration::CalibrationSet& set, bool on_usb, int vendor, int product,
                                            int force_axes) {
  for (const auto& d : set.devices())
    if (on_usb && d.usb_vendor_id == vendor && d.usb_product_id == product && (force_axes == 0 || d.axes == force_axes))
      return &d;
  // Only files for another number of axes (a joystick whose own file is gone, and the wheel's is
  // there): no file for this device; a wheel's file would play a joystick's one axis.
  return nullptr;
}

void set_node(OpenedDevice& out, std::uint16_t vendor, std::uint16_t product, const std::string& name, const std::string& path,
              const char* transport) {
  usb::UsbHidDeviceInfo info;
  info.vendor_id = vendor;
  info.product_id = product;
  info.product = name;
  out.usb = info;
  out.node = path;
  out.transport = transport;
}

bool serves_hidraw(const DeviceSpec& spec, const DeviceCalibration*) { return !hidraw_request(spec).empty(); }

bool is_hidraw_device(const std::string& device) { return device == "hidraw" || device.rfind("hidraw:", 0) == 0; }

std::string hidraw_calibration(const calibration::CalibrationSet& set, const DeviceSpec& spec, const DeviceCalibration* cal) {
  refuse_simulated_hands(spec);
  return choose_hidraw(set, spec, cal).calibration->name;
}

OpenedDevice open_hidraw(const calibration::CalibrationSet& set, DeviceSpec& spec, const DeviceCalibration* cal) {
  refuse_simulated_hands(spec);
  const HidrawChoice choice = choose_hidraw(set, spec, cal);
  const DeviceCalibration& found = *choice.calibration;
  const auto& node = choice.node;
  const std::string ids = usb_ids(node.vendor_id, node.product_id);
  const std::string help = "  permission to open " + node.path + " is missing; add this line to "
                           "/etc/udev/rules.d/70-sandpaper.rules (the .deb installs it for the devices it knows):\n    " +
                           hidraw_udev_rule(node.vendor_id, node.product_id) +
                           "\n  then run `sudo udevadm control --reload` and unplug and replug the device\n";
  std::unique_ptr<usb::HidrawTransport> transport;
  std::string message;
  const UsbStatus opened = usb::HidrawTransport::open(node.path, transport, message);
  if (opened != UsbStatus::Ok)
    throw DeviceOpenError(opened == UsbStatus::AccessDenied ? Cause::AccessDenied : Cause::NoUsb,
                          "cannot open " + node.path + " (" + found.name + ", " + ids + "): " + message,
                          opened == UsbStatus::AccessDenied ? help : "");
  OpenedDevice out = open_hid_pid(std::move(transport), found, spec, node.path + " (" + found.name + ", " + ids + ")", help);
  out.description = found.name + " (" + ids + ") through " + node.path + ", the kernel's driver left bound";
  set_node(out, node.vendor_id, node.product_id, node.name, node.path, "hidraw");
  return out;
}

}  // namespace sandpaper::runtime
