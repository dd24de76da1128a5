// The udev rules file the Debian package installs (and `sandpaper devices --udev-rules` prints):
// the seat's user may open, without root, the hidraw nodes of every joystick a calibration file
// names and every input event device that declares force feedback (docs/DEVICES.md "No root").
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "sandpaper/runtime/devices/open_device.hpp"

namespace sandpaper::runtime {

std::string udev_rules_file(const calibration::CalibrationSet& set) {
  std::string s =
      "# Sandpaper: force-feedback devices for the logged-in user, without root (docs/DEVICES.md).\n"
      "# TAG+=\"uaccess\" lets systemd-logind give the seat's user the node; it must come before\n"
      "# 73-seat-late.rules, hence 70-. Made by `sandpaper devices --udev-rules` from the calibration files.\n"
      "\n"
      "# hidraw nodes of the joysticks a device calibration names (`--device hidraw`; usbhid stays bound).\n";
  // One rule per USB ID, naming every file for it (a board's joystick and wheel share one).
  std::vector<std::pair<std::pair<int, int>, std::string>> ids;
  for (const auto& d : set.devices()) {
    if (d.usb_vendor_id < 0) continue;
    const std::pair<int, int> id{d.usb_vendor_id, d.usb_product_id};
    const auto at = std::find_if(ids.begin(), ids.end(), [&](const auto& e) { return e.first == id; });
    if (at == ids.end()) ids.push_back({id, d.name});
    else at->second += ", " + d.name;
  }
  for (const auto& [id, names] : ids) s += "# " + names + "\n" + hidraw_udev_rule(id.first, id.second) + "\n";
  if (ids.empty()) s += "# (no device calibration names a USB device)\n";
  // capabilities/ff is the input device's force-feedback bitmap in hex words ("0" without any):
  // a digit other than 0 anywhere in it means the device takes EV_FF effects.
  s += "\n# input event devices with force feedback, joystick or wheel (the kernel's EVIOCSFF interface).\n"
       "SUBSYSTEM==\"input\", KERNEL==\"event*\", ATTRS{capabilities/ff}==\"*[1-9a-f]*\", TAG+=\"uaccess\"\n";
  return s;
}

}  // namespace sandpaper::runtime
