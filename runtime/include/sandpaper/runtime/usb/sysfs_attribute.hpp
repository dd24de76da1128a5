#pragma once
// Reading Linux sysfs attributes, which the device families read to find and describe devices.
#include <filesystem>
#include <string>

namespace sandpaper::runtime::usb {

// The first line of a sysfs attribute file, without its newline; "" if it cannot be read.
std::string sysfs_first_line(const std::filesystem::path& attribute);

}  // namespace sandpaper::runtime::usb
