#include "sandpaper/runtime/devices/builtin_devices.hpp"

#include <string>
#include <vector>

#include "embedded_device_files.hpp"

namespace sandpaper::runtime {

const calibration::CalibrationSet& builtin_devices() {
  static const calibration::CalibrationSet set = [] {
    std::vector<calibration::DeviceCalibration> devices;
    for (const auto& file : detail::embedded_device_files())
      devices.push_back(calibration::parse_device_text(std::string(file.text), std::string(file.shown_as)));
    return calibration::CalibrationSet::of_devices(std::move(devices));
  }();
  return set;
}

}  // namespace sandpaper::runtime
