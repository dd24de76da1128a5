#pragma once
// The devices the runtime carries with it: the simulated joystick of calibration/devices/sim.toml,
// compiled in. For opening it through the factory (open_device) where no calibration folder is at
// hand: Player::simulated, the C API, Python.
#include "sandpaper/calibration/calibration.hpp"

namespace sandpaper::runtime {

// A set holding only the device "sim", read from the embedded sim.toml once. Throws
// calibration::CalibrationError only if the embedded file were invalid.
const calibration::CalibrationSet& builtin_devices();

}  // namespace sandpaper::runtime
