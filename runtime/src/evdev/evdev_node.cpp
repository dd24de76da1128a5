#include "sandpaper/runtime/evdev/evdev_node.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "sandpaper/runtime/usb/sysfs_attribute.hpp"

namespace sandpaper::runtime::evdev {
namespace fs = std::filesystem;
using usb::sysfs_first_line;

namespace {

std::uint16_t hex16(const fs::path& p) {
  const std::string s = sysfs_first_line(p);
  char* end = nullptr;
  const unsigned long v = std::strtoul(s.c_str(), &end, 16);
  return end == s.c_str() || v > 0xFFFF ? 0 : static_cast<std::uint16_t>(v);
}

int node_number(const std::string& name) { return std::atoi(name.c_str() + 5); }  // "event12" -> 12

constexpr unsigned kEvFf = 0x15;  // EV_FF

// The interrupt OUT endpoint of the USB interface a HID device hangs from: usbhid sends output
// reports one at a time on it, one per interval (Linux drivers/usb/core/endpoint.c prints the
// interval; ep_XX folders sit in the interface's folder, the HID device's parent).
double out_interval_of(const fs::path& hid_device) {
  std::error_code ec;
  const fs::path interface = fs::canonical(hid_device, ec).parent_path();
  if (ec) return 0;
  for (fs::directory_iterator it(interface, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().filename().string().rfind("ep_", 0) != 0) continue;
    if (sysfs_first_line(it->path() / "direction") != "out" || sysfs_first_line(it->path() / "type") != "Interrupt") continue;
    return sysfs_interval_s(sysfs_first_line(it->path() / "interval"));
  }
  return 0;
}

}  // namespace

double sysfs_interval_s(const std::string& text) noexcept {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !(v > 0) || v > 1e6) return 0;
  const std::string unit(end);
  return unit == "ms" ? v * 1e-3 : unit == "us" ? v * 1e-6 : 0;
}

bool sysfs_bit(const std::string& bitmap, unsigned bit, unsigned word_bits) noexcept {
  std::vector<std::string> words;
  std::istringstream in(bitmap);
  for (std::string w; in >> w;) words.push_back(w);
  const std::size_t index = bit / word_bits;  // counted from the last word
  if (words.empty() || index >= words.size()) return false;
  const std::string& w = words[words.size() - 1 - index];
  if (w.size() > word_bits / 4 || w.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos) return false;
  const unsigned shift = bit % word_bits;
  const std::size_t digit = shift / 4;  // from the right
  if (digit >= w.size()) return false;
  const char c = w[w.size() - 1 - digit];
  const int value = c <= '9' ? c - '0' : (c | 0x20) - 'a' + 10;
  return (value >> (shift % 4)) & 1;
}

std::vector<EvdevNode> list_force_feedback_nodes(const std::string& sysfs_root) {
  std::vector<std::pair<int, EvdevNode>> found;
  std::error_code ec;
  for (fs::directory_iterator it(fs::path(sysfs_root) / "class/input", ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind("event", 0) != 0 || name.size() == 5) continue;
    const fs::path input = it->path() / "device";  // the input device (inputN) the node belongs to
    const std::string ev = sysfs_first_line(input / "capabilities/ev");
    if (!sysfs_bit(ev, kEvFf)) continue;
    EvdevNode n;
    n.path = "/dev/input/" + name;
    n.name = sysfs_first_line(input / "name");
    n.bustype = hex16(input / "id/bustype");
    n.vendor_id = hex16(input / "id/vendor");
    n.product_id = hex16(input / "id/product");
    const std::string ff = sysfs_first_line(input / "capabilities/ff");
    n.constant_force = sysfs_bit(ff, kFfConstant);
    n.gain = sysfs_bit(ff, kFfGain);
    n.autocenter = sysfs_bit(ff, kFfAutocenter);
    const std::string abs = sysfs_first_line(input / "capabilities/abs");
    n.axes = sysfs_bit(abs, kAbsX) ? (sysfs_bit(abs, kAbsY) ? 2 : 1) : sysfs_bit(abs, kAbsWheel) ? 1 : 0;
    if (const fs::path d = input / "device/report_descriptor"; fs::exists(d, ec)) n.report_descriptor = d.string();
    if (n.usb()) n.out_interval_s = out_interval_of(input / "device");
    found.emplace_back(node_number(name), std::move(n));
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<EvdevNode> out;
  for (auto& f : found) out.push_back(std::move(f.second));
  return out;
}

const EvdevNode* find_node(const std::vector<EvdevNode>& nodes, const std::string& path) {
  std::error_code ec;
  const fs::path real = fs::canonical(path, ec);
  const std::string wanted = ec ? path : real.string();
  for (const auto& n : nodes)
    if (n.path == wanted) return &n;
  return nullptr;
}

}  // namespace sandpaper::runtime::evdev
