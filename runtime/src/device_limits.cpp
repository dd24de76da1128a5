#include "sandpaper/runtime/device_limits.hpp"

namespace sandpaper::runtime {

DeviceLimits limits_of(const calibration::DeviceCalibration& device) {
  DeviceLimits limits;
  limits.name = device.name;
  limits.max_force_N = device.max_force_N;
  limits.min_rate_hz = device.min_rate_hz;
  limits.max_rate_hz = device.max_rate_hz;
  limits.workspace_radius_m = device.workspace_radius_m;
  return limits;
}

}  // namespace sandpaper::runtime
