#pragma once
// A device calibration file's limits as the runtime holds them.
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/runtime/device.hpp"

namespace sandpaper::runtime {

// The device limits (SI) a device calibration states: its name, maximum force, servo rates and
// workspace radius.
DeviceLimits limits_of(const calibration::DeviceCalibration& device);

}  // namespace sandpaper::runtime
