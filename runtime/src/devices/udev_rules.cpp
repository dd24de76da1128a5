// The udev rules file the Debian package installs (and `sandpaper devices --udev-rules` prints):
// the seat's user may open, without root, the hidraw nodes of every joystick a calibration file
// names and every input event device that declares force feedback (docs/DEVICES.md "No root").
#include <string>

#include "sandpaper/runtime/devices/open_device.hpp"

namespace sandpaper::runtime {

std::string udev_rules_file(const calibration::CalibrationSet& set) {
  std::string s =
      "# Sandpaper: force-feedback devices for the logged-in user, without root (docs/DEVICES.md).\n"
      "# TAG+=\"uaccess\" lets systemd-logind give the seat's user the node; it must come before\n"
      "# 73-seat-late.rules, hence 70-. Made by `sandpaper devices --udev-rules` from the calibration files.\n"
      "\n"
      "# hidraw nodes of the joysticks a device calibration names (`--device hidraw`; usbhid stays bound).\n";
  bool any = false;
  for (const auto& d : set.devices())
    if (d.usb_vendor_id >= 0) {
      s += "# " + d.name + "\n" + hidraw_udev_rule(d.usb_vendor_id, d.usb_product_id) + "\n";
      any = true;
    }
  if (!any) s += "# (no device calibration names a USB device)\n";
  // capabilities/ff is the input device's force-feedback bitmap in hex words ("0" without any):
  // a digit other than 0 anywhere in it means the device takes EV_FF effects.
  s += "\n# input event devices with force feedback, joystick or wheel (the kernel's EVIOCSFF interface).\n"
       "SUBSYSTEM==\"input\", KERNEL==\"event*\", ATTRS{capabilities/ff}==\"*[1-9a-f]*\", TAG+=\"uaccess\"\n";
  return s;
}

}  // namespace sandpaper::runtime
