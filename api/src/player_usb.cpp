// sandpaper::Player::usb: the first calibrated USB HID PID joystick plugged in (docs/USB_PID.md),
// opened through the device factory as `sandpaper run --device usb` opens it.
#include <string>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/runtime/devices/open_device.hpp"
#include "sandpaper/sandpaper.hpp"

namespace sandpaper {
namespace {

// An exception's text is one line: each line break and the indent after it become "; ".
std::string one_line(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\n') {
      out += text[i];
      continue;
    }
    while (i + 1 < text.size() && text[i + 1] == ' ') ++i;
    if (i + 1 < text.size()) out += "; ";
  }
  return out;
}

}  // namespace

Player Player::usb(const Library& library) { return usb(library.compiler().calibration()); }

Player Player::usb(const calibration::CalibrationSet& set) {
  runtime::DeviceSpec spec;
  spec.device = "usb";
  runtime::OpenedDevice opened;
  try {
    opened = runtime::open_device(set, std::move(spec));
  } catch (const runtime::DeviceOpenError& e) {
    throw DeviceError(one_line(std::string(e.what()) + (e.help.empty() ? "" : "\n" + e.help)));
  }
  Player p(std::move(opened.device));
  p.set_device_calibration_nonrt(opened.calibration);
  return p;
}

}  // namespace sandpaper
