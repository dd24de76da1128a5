#include "sandpaper/shapes/device3.hpp"

#include <cmath>
#include <stdexcept>

#include "embedded_sim3d_file.hpp"

namespace sandpaper::shapes {

bool Workspace3::contains(const glm::dvec3& p_m) const noexcept {
  const glm::dvec3 half = 0.5 * size_m;
  if (sphere) return p_m.x * p_m.x + p_m.y * p_m.y + p_m.z * p_m.z <= half.x * half.x;
  return std::abs(p_m.x) <= half.x && std::abs(p_m.y) <= half.y && std::abs(p_m.z) <= half.z;
}

DeviceLimits3 limits3_of(const calibration::DeviceCalibration& device) {
  if (!device.three_axis())
    throw std::invalid_argument("device '" + device.name + "' has " + std::to_string(device.axes) +
                                " force axis(es), not three: a 3-D scene is felt on a 3-DOF device (sim3d, or a file with [force.z])");
  DeviceLimits3 limits;
  limits.name = device.name;
  limits.max_force_N = device.max_force_N;
  limits.min_rate_hz = device.min_rate_hz;
  limits.max_rate_hz = device.max_rate_hz;
  limits.workspace.sphere = device.workspace_circle;
  limits.workspace.size_m = {device.workspace_size_m[0], device.workspace_size_m[1], device.workspace_size_m[2]};
  return limits;
}

const calibration::DeviceCalibration& sim3d_calibration() {
  static const calibration::DeviceCalibration device = [] {
    const auto& file = detail::embedded_sim3d_files().front();
    return calibration::parse_device_text(std::string(file.text), std::string(file.shown_as));
  }();
  return device;
}

const DeviceLimits3& sim3d_limits() {
  static const DeviceLimits3 limits = limits3_of(sim3d_calibration());
  return limits;
}

}  // namespace sandpaper::shapes
