// What the device families read from sysfs (sysfs_bit on an input device's capabilities/ev, ff and
// abs; sysfs_interval_s on an endpoint's interval; usb_port_name on a USB device's folder name and
// usb_address_text on its devnum, which name a reset): the kernel writes these, but a reader must
// not trust a file it did not write.
//
// Checked: for text the kernel could have written (hex words of at most 16 digits, one space
// between them), every bit agrees with a decoder that reads each word with strtoull; for any text,
// no crash and no bit past the words given. An interval is 0 or a finite time of at most 1000 s,
// and the kernel's own form (digits then "ms" or "us") reads as its value. A port path is accepted
// exactly when std::regex accepts it as bus-port(.port)*; an address exactly when it is 1-127 in
// at most three digits, with or without the kernel's newline.
#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "sandpaper/runtime/devices/usb_port.hpp"
#include "sandpaper/runtime/evdev/evdev_node.hpp"

namespace {

bool kernel_like(const std::string& text, std::vector<std::uint64_t>& words) {
  std::istringstream in(text);
  std::string w, rebuilt;
  while (in >> w) {
    if (w.size() > 16 || w.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos) return false;
    words.push_back(std::strtoull(w.c_str(), nullptr, 16));
    rebuilt += (rebuilt.empty() ? "" : " ") + w;
  }
  return !words.empty() && rebuilt == text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using sandpaper::fuzz::check;
  using sandpaper::runtime::evdev::sysfs_bit;
  using sandpaper::runtime::evdev::sysfs_interval_s;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::uint64_t> words;
  const bool wellformed = kernel_like(text, words);
  const unsigned bits = static_cast<unsigned>(std::min<std::size_t>(64 * (words.size() + 1), 4096));
  for (unsigned bit = 0; bit < bits; ++bit) {
    const bool got = sysfs_bit(text, bit);
    if (!wellformed) continue;
    const std::size_t index = bit / 64;
    const bool want = index < words.size() && ((words[words.size() - 1 - index] >> (bit % 64)) & 1);
    check(got == want, "bit " + std::to_string(bit) + " of '" + text + "' read as " + (got ? "set" : "clear"));
  }
  const double interval = sysfs_interval_s(text);
  check(interval == 0 || (std::isfinite(interval) && interval > 0 && interval <= 1000), "interval of '" + text + "' out of range");
  const std::size_t digits = text.find_first_not_of("0123456789");
  if (digits > 0 && digits != std::string::npos && digits <= 6 && text.size() == digits + 2 && text[digits + 1] == 's' &&
      (text[digits] == 'm' || text[digits] == 'u')) {
    const double value = std::strtod(text.c_str(), nullptr) * (text[digits] == 'm' ? 1e-3 : 1e-6);
    check(interval == value, "interval '" + text + "' read as " + std::to_string(interval));
  }
  static const std::regex port_path("[0-9]{1,3}-[0-9]{1,3}(\\.[0-9]{1,3})*");
  check(sandpaper::runtime::usb_port_name(text) == std::regex_match(text, port_path), "port path '" + text + "' misread");
  static const std::regex address("[0-9]{1,3}\n?");
  const int devnum = sandpaper::runtime::usb_address_text(text);
  const bool is_address = std::regex_match(text, address) && std::atoi(text.c_str()) >= 1 && std::atoi(text.c_str()) <= 127;
  check(is_address ? devnum == std::atoi(text.c_str()) : devnum == 0, "address '" + text + "' read as " + std::to_string(devnum));
  return 0;
}
