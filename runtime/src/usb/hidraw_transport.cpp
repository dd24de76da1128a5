#include "sandpaper/runtime/usb/hidraw_transport.hpp"

#include <fcntl.h>
#include <linux/hidraw.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sandpaper/runtime/usb/hid_descriptor.hpp"
#include "sandpaper/runtime/usb/libusb_transport.hpp"

namespace sandpaper::runtime::usb {
namespace fs = std::filesystem;

namespace {

// hidraw's errors as UsbStatus. A node whose device has gone answers ENODEV (write, ioctl) or EIO
// (read); usbhid passes a STALL up as EPIPE.
UsbStatus named(int error) noexcept {
  switch (error) {
    case ENODEV: case ENOENT: case ENXIO: case ESHUTDOWN: return UsbStatus::NoDevice;
    case EACCES: case EPERM: return UsbStatus::AccessDenied;
    case EBUSY: return UsbStatus::Busy;
    case ETIMEDOUT: case EAGAIN: return UsbStatus::Timeout;
    case EPIPE: return UsbStatus::Stalled;
    case EINVAL: case EOPNOTSUPP: return UsbStatus::NotSupported;
    default: return UsbStatus::Other;
  }
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

int node_number(const std::string& name) {
  return name.size() > 6 ? std::atoi(name.c_str() + 6) : -1;  // "hidraw12" -> 12
}

}  // namespace

bool parse_hid_uevent(const std::string& uevent, HidrawNode& node) {
  bool found = false;
  std::istringstream in(uevent);
  for (std::string line; std::getline(in, line);) {
    unsigned bus = 0, vendor = 0, product = 0;
    char end = 0;
    if (line.rfind("HID_ID=", 0) == 0 &&
        std::sscanf(line.c_str() + 7, "%4x:%8x:%8x%c", &bus, &vendor, &product, &end) == 3 && vendor <= 0xFFFF &&
        product <= 0xFFFF) {
      node.usb = bus == 3;
      node.vendor_id = static_cast<std::uint16_t>(vendor);
      node.product_id = static_cast<std::uint16_t>(product);
      found = true;
    } else if (line.rfind("HID_NAME=", 0) == 0) {
      node.name = line.substr(9);
    }
  }
  return found;
}

std::vector<HidrawNode> list_hidraw_nodes() {
  std::vector<HidrawNode> out;
  std::error_code ec;
  for (fs::directory_iterator it("/sys/class/hidraw", ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind("hidraw", 0) != 0) continue;
    HidrawNode node;
    node.path = "/dev/" + name;
    if (!parse_hid_uevent(read_text(it->path() / "device" / "uevent"), node)) continue;
    const std::string d = read_text(it->path() / "device" / "report_descriptor");
    if (!d.empty()) {
      UsbHidDeviceInfo info;
      summarise_report_descriptor(std::span(reinterpret_cast<const std::uint8_t*>(d.data()), d.size()), info);
      node.descriptor_read = info.descriptor_read;
      node.has_pid = info.has_pid;
      node.force_axes = info.force_axes;
      node.descriptor_error = info.descriptor_error;
    }
    out.push_back(std::move(node));
  }
  std::sort(out.begin(), out.end(), [](const HidrawNode& a, const HidrawNode& b) {
    return node_number(a.path.substr(5)) < node_number(b.path.substr(5));
  });
  return out;
}

UsbStatus HidrawTransport::open(const std::string& path, std::unique_ptr<HidrawTransport>& out, std::string& message) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int e = errno;
    message = path + ": " + std::strerror(e);
    return named(e);
  }
  hidraw_devinfo info{};
  if (::ioctl(fd, HIDIOCGRAWINFO, &info) < 0) {
    const int e = errno;
    message = path + " is not a hidraw node: " + std::strerror(e);
    ::close(fd);
    return named(e) == UsbStatus::NoDevice ? UsbStatus::NoDevice : UsbStatus::NotSupported;
  }
  out.reset(new HidrawTransport);
  out->fd_ = fd;
  out->path_ = path;
  return UsbStatus::Ok;
}

HidrawTransport::~HidrawTransport() {
  if (fd_ >= 0) ::close(fd_);
}

UsbStatus HidrawTransport::report_descriptor(std::vector<std::uint8_t>& descriptor) {
  int size = 0;
  if (::ioctl(fd_, HIDIOCGRDESCSIZE, &size) < 0) return named(errno);
  hidraw_report_descriptor d{};
  d.size = static_cast<std::uint32_t>(std::clamp(size, 0, HID_MAX_DESCRIPTOR_SIZE));
  if (::ioctl(fd_, HIDIOCGRDESC, &d) < 0) return named(errno);
  descriptor.assign(d.value, d.value + d.size);
  // Whether reports carry an ID byte decides hidraw's framing; a descriptor the parser refuses is
  // refused again, with its reason, by the driver that asked for it.
  try {
    numbered_ = parse_hid_report_descriptor(descriptor).uses_report_ids;
  } catch (const HidDescriptorError&) {
  }
  return UsbStatus::Ok;
}

UsbStatus HidrawTransport::failed(int error) noexcept {
  const UsbStatus s = named(error);
  if (s != UsbStatus::Other) return s;
  // A device that leaves the bus fails the transfer in flight with an I/O error (EPROTO, EILSEQ:
  // no answer; Linux's Documentation/driver-api/usb/error-codes.rst) before hidraw learns it is
  // gone; once it has, poll() says so on this descriptor (POLLHUP), even if the device is already
  // back under a new node. A device that stays had a transfer fail. The hub notices a port change
  // on its own schedule: in the USB lab's guest a reset took longer than 100 ms to reach hidraw,
  // so this waits up to a second, on the driver's I/O thread, only after such an error. (The
  // libusb transport asks the device for its status instead: hidraw cannot.)
  pollfd p{fd_, 0, 0};
  return ::poll(&p, 1, 1000) > 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0 ? UsbStatus::NoDevice : s;
}

UsbStatus HidrawTransport::read_input(std::span<std::uint8_t> buffer, std::size_t& length, unsigned timeout_ms) noexcept {
  length = 0;
  pollfd p{fd_, POLLIN, 0};
  const int n = ::poll(&p, 1, static_cast<int>(std::min<unsigned>(timeout_ms, 60'000)));
  if (n < 0) return errno == EINTR ? UsbStatus::Timeout : failed(errno);
  if (n == 0) return UsbStatus::Timeout;
  if (p.revents & (POLLHUP | POLLERR | POLLNVAL)) return UsbStatus::NoDevice;
  const ssize_t got = ::read(fd_, buffer.data(), buffer.size());
  if (got < 0) return errno == EIO ? UsbStatus::NoDevice : failed(errno);
  length = static_cast<std::size_t>(got);
  return UsbStatus::Ok;
}

UsbStatus HidrawTransport::write_output(std::span<const std::uint8_t> report) noexcept {
  std::array<std::uint8_t, 1 + 256> framed{};
  const std::uint8_t* data = report.data();
  std::size_t size = report.size();
  if (!numbered_) {  // hidraw's first byte is the report number, 0 for a descriptor without IDs
    if (size + 1 > framed.size()) return UsbStatus::Other;
    std::copy_n(report.data(), size, framed.begin() + 1);
    data = framed.data();
    ++size;
  }
  const ssize_t put = ::write(fd_, data, size);
  if (put < 0) return failed(errno);
  return static_cast<std::size_t>(put) == size ? UsbStatus::Ok : UsbStatus::Other;
}

UsbStatus HidrawTransport::set_feature(std::span<const std::uint8_t> report) {
  std::vector<std::uint8_t> framed;
  if (!numbered_) framed.push_back(0);
  framed.insert(framed.end(), report.begin(), report.end());
  if (::ioctl(fd_, HIDIOCSFEATURE(framed.size()), framed.data()) < 0) return failed(errno);
  return UsbStatus::Ok;
}

UsbStatus HidrawTransport::get_feature(std::uint8_t report_id, std::span<std::uint8_t> buffer, std::size_t& length) {
  length = 0;
  std::vector<std::uint8_t> framed(buffer.size() + (numbered_ ? 0 : 1), 0);
  if (framed.empty()) return UsbStatus::Other;
  framed[0] = numbered_ ? report_id : 0;
  const int got = ::ioctl(fd_, HIDIOCGFEATURE(framed.size()), framed.data());
  if (got < 0) return failed(errno);
  const std::size_t skip = numbered_ ? 0 : 1;  // hidraw's report-number byte, not on the wire
  length = std::min(buffer.size(), static_cast<std::size_t>(got) > skip ? static_cast<std::size_t>(got) - skip : 0);
  std::copy_n(framed.begin() + static_cast<std::ptrdiff_t>(skip), length, buffer.begin());
  return UsbStatus::Ok;
}

}  // namespace sandpaper::runtime::usb
