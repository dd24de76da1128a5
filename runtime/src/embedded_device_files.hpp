#pragma once
// Device calibration files compiled into the runtime (generated from calibration/devices/ by
// cmake/embed_files.cmake), so that what a file states is stated once: sim.toml gives the simulated
// device's limits to every caller, with or without a calibration folder at hand.
#include <string_view>
#include <vector>

namespace sandpaper::runtime::detail {

struct EmbeddedDeviceFile {
  std::string_view shown_as;  // "calibration/devices/sim.toml", as messages name it
  std::string_view text;
};
const std::vector<EmbeddedDeviceFile>& embedded_device_files();

}  // namespace sandpaper::runtime::detail
