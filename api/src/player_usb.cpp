// sandpaper::Player::usb and Player::open: a calibrated joystick found on the bus (docs/DEVICES.md),
// opened through the device factory as `sandpaper run --device usb|hidraw[:PATH]` opens it.
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

Player Player::usb(const Library& library) { return open(library.compiler().calibration(), "usb"); }

Player Player::usb(const calibration::CalibrationSet& set) { return open(set, "usb"); }

Player Player::open(const Library& library, const std::string& device, PlayerOpenOptions options) {
  return open(library.compiler().calibration(), device, options);
}

Player Player::open(const calibration::CalibrationSet& set, const std::string& device, PlayerOpenOptions options) {
  runtime::DeviceSpec spec;
  spec.device = device;
  spec.uncalibrated = options.uncalibrated;
  runtime::OpenedDevice opened;
  try {
    // Only a joystick on the bus: the simulated ones are moved by a hand Player::simulated scripts.
    if (!runtime::choose_device(set, spec).real)
      throw DeviceError("a player opened on a device plays a joystick found on the bus (usb, hidraw[:PATH], evdev[:PATH]), not '" + device +
                        "'; the simulated joystick has a player of its own (Player::simulated, sp_player_open_simulated, "
                        "sandpaper.Player.simulated)");
    opened = runtime::open_device(set, std::move(spec));
  } catch (const runtime::DeviceOpenError& e) {
    throw DeviceError(one_line(std::string(e.what()) + (e.help.empty() ? "" : "\n" + e.help)));
  }
  Player p(std::move(opened.device));
  p.set_device_calibration_nonrt(opened.calibration);
  p.set_warning_nonrt(opened.warning);
  return p;
}

}  // namespace sandpaper
