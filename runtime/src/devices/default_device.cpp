// The path `run` takes when no --device is given (docs/DEVICES.md, "Without --device"): a calibrated
// joystick plugged in, through a path that leaves the kernel's driver bound, else the simulator.
#include <unistd.h>

#include "devices_internal.hpp"
#include "sandpaper/runtime/evdev/evdev_node.hpp"
#include "sandpaper/runtime/usb/hidraw_transport.hpp"

namespace sandpaper::runtime {

namespace {
bool may_open(const std::string& path) { return ::access(path.c_str(), R_OK | W_OK) == 0; }

}  // namespace

DefaultDevice default_play_device(const calibration::CalibrationSet& set) {
  // hidraw first: Sandpaper's own HID PID driver, whose device model explain predicts; evdev for a
  // calibrated device this user may open only there. A node nobody here may open is still named,
  // so that the open error gives the rule that opens it.
  std::string denied;
  for (const auto& n : usb::list_hidraw_nodes())
    if (const auto* cal = usb_calibration_of(set, n.usb, n.vendor_id, n.product_id, n.force_axes)) {
      if (may_open(n.path)) return {"hidraw:" + n.path, cal->name + " (" + usb_ids(n.vendor_id, n.product_id) + ") through " + n.path};
      if (denied.empty()) denied = "hidraw:" + n.path;
    }
  for (const auto& n : evdev::list_force_feedback_nodes())
    if (const auto* cal = usb_calibration_of(set, n.usb(), n.vendor_id, n.product_id, force_axes_of(n));
        cal != nullptr && n.constant_force) {
      if (may_open(n.path)) return {"evdev:" + n.path, cal->name + " (" + usb_ids(n.vendor_id, n.product_id) + ") through " + n.path};
      if (denied.empty()) denied = "evdev:" + n.path;
    }
  if (!denied.empty()) return {denied, "a calibrated joystick this user may not open yet"};
  // Any other force-feedback device this user may play: named rather than passed over for the
  // simulator, so that the run says it plays only with --uncalibrated (or plays, given it).
  for (const auto& n : evdev::list_force_feedback_nodes())
    if (n.constant_force && n.axes > 0 && may_open(n.path))
      return {"evdev:" + n.path, "'" + n.name + "' (" + usb_ids(n.vendor_id, n.product_id) + ") through " + n.path +
                                     ", which no calibration file names"};
  return {"sim", ""};
}

}  // namespace sandpaper::runtime
