#include "sandpaper/runtime/usb/sysfs_attribute.hpp"

#include <fstream>

namespace sandpaper::runtime::usb {

std::string sysfs_first_line(const std::filesystem::path& attribute) {
  std::ifstream in(attribute);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace sandpaper::runtime::usb
