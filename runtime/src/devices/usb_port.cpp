#include "sandpaper/runtime/devices/usb_port.hpp"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include "sandpaper/runtime/usb/sysfs_attribute.hpp"

namespace sandpaper::runtime {
namespace fs = std::filesystem;
using usb::sysfs_first_line;

namespace {

// idVendor and idProduct: four hex digits. 0 for anything else (0000 is no vendor USB-IF assigns).
std::uint16_t hex_id(const std::string& text) {
  if (text.size() != 4 || text.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos) return 0;
  return static_cast<std::uint16_t>(std::strtoul(text.c_str(), nullptr, 16));
}

std::optional<UsbPort> read_port(const fs::path& folder) {
  UsbPort port;
  port.name = folder.filename().string();
  if (!usb_port_name(port.name)) return std::nullopt;
  port.devnum = usb_address_text(sysfs_first_line(folder / "devnum"));
  port.vendor_id = hex_id(sysfs_first_line(folder / "idVendor"));
  port.product_id = hex_id(sysfs_first_line(folder / "idProduct"));
  if (port.devnum == 0 || port.vendor_id == 0) return std::nullopt;
  return port;
}

}  // namespace

// port-path = bus "-" port *( "." port ) ; bus, port = 1*3DIGIT
bool usb_port_name(const std::string& name) noexcept {
  std::size_t i = 0, digits = 0;
  bool dash = false;
  for (; i < name.size(); ++i) {
    const char c = name[i];
    if (c >= '0' && c <= '9') {
      if (++digits > 3) return false;
    } else if ((c == '-' && !dash) || (c == '.' && dash)) {
      if (digits == 0) return false;
      dash = true;
      digits = 0;
    } else {
      return false;
    }
  }
  return dash && digits > 0;
}

int usb_address_text(const std::string& text) noexcept {
  std::size_t n = text.size();
  if (n > 0 && text[n - 1] == '\n') --n;
  if (n == 0 || n > 3) return 0;
  int v = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (text[i] < '0' || text[i] > '9') return 0;
    v = v * 10 + (text[i] - '0');
  }
  return v >= 1 && v <= 127 ? v : 0;
}

std::optional<UsbPort> usb_port_of_sysfs(const std::string& sysfs_path) {
  std::error_code ec;
  fs::path p = fs::canonical(sysfs_path, ec);
  if (ec) return std::nullopt;
  for (; !p.empty() && p != p.root_path(); p = p.parent_path())
    if (auto port = read_port(p)) return port;
  return std::nullopt;
}

std::optional<UsbPort> usb_port_of_address(int bus, int address, const std::string& sysfs_root) {
  std::error_code ec;
  for (fs::directory_iterator it(fs::path(sysfs_root) / "bus/usb/devices", ec), end; !ec && it != end; it.increment(ec)) {
    auto port = read_port(it->path());
    if (!port || port->devnum != address) continue;
    // The bus number is the port path's first field; busnum says the same.
    if (std::atoi(port->name.c_str()) == bus) return port;
  }
  return std::nullopt;
}

std::optional<UsbPort> usb_port_of_node(const std::string& node, const std::string& sysfs_root) {
  const std::string base = fs::path(node).filename().string();
  const char* subsystem = base.rfind("hidraw", 0) == 0 ? "class/hidraw" : base.rfind("event", 0) == 0 ? "class/input" : nullptr;
  if (subsystem == nullptr) return std::nullopt;
  return usb_port_of_sysfs((fs::path(sysfs_root) / subsystem / base / "device").string());
}

bool came_back_nonrt(const UsbPort& port, double grace_s, const std::string& sysfs_root) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(grace_s);
  const fs::path folder = fs::path(sysfs_root) / "bus/usb/devices" / port.name;
  for (;;) {
    const auto now_there = read_port(folder);
    if (now_there && now_there->devnum != port.devnum && now_there->vendor_id == port.vendor_id &&
        now_there->product_id == port.product_id)
      return true;
    if (std::chrono::steady_clock::now() >= until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace sandpaper::runtime
