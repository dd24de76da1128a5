#include "functionfs_device.hpp"

#include <fcntl.h>
#include <linux/usb/functionfs.h>
#include <poll.h>
#include <pthread.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace sandpaper::usb_lab {
namespace {

void put_le16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put_le32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void set_le32(std::vector<std::uint8_t>& out, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

[[noreturn]] void fail(const std::string& what) {
  throw std::runtime_error(what + ": " + std::strerror(errno));
}

// Blocked endpoint reads and writes are interrupted by this signal at stop(); the handler does
// nothing, it only makes the system call return EINTR (installed without SA_RESTART).
constexpr int kWakeSignal = SIGUSR1;
void on_wake(int) {}
void install_wake_handler() {
  struct sigaction action {};
  action.sa_handler = on_wake;
  sigemptyset(&action.sa_mask);
  sigaction(kWakeSignal, &action, nullptr);
}

// FunctionFS wants the function's strings as one table per language, indexed from 1 in the order
// the descriptors use them; the firmware numbers its strings device-wide. So every string index in
// the function's descriptors is renumbered 1..n here, and the table holds those strings.
struct RenumberedStrings {
  std::vector<std::uint8_t> descriptors;
  std::vector<std::string> strings;
};

RenumberedStrings renumber_strings(const UsbFunction& function) {
  RenumberedStrings out{function.function_descriptors(), {}};
  auto& d = out.descriptors;
  for (std::size_t at = 0; at + 2 <= d.size() && d[at] >= 2; at += d[at]) {
    if (d[at + 1] == 0x04 && d[at] >= 9 && d[at + 8] != 0) {  // interface descriptor: iInterface
      out.strings.push_back(function.string_descriptor(d[at + 8]));
      d[at + 8] = static_cast<std::uint8_t>(out.strings.size());
    }
  }
  return out;
}

std::size_t count_descriptors(const std::vector<std::uint8_t>& d) {
  std::size_t n = 0;
  for (std::size_t at = 0; at + 2 <= d.size() && d[at] >= 2; at += d[at]) ++n;
  return n;
}

}  // namespace

FunctionFsDevice::FunctionFsDevice(std::string ffs_dir, UsbFunction& function)
    : dir_(std::move(ffs_dir)), function_(function) {
  ep0_ = ::open((dir_ + "/ep0").c_str(), O_RDWR);
  if (ep0_ < 0) fail(dir_ + "/ep0");
}

FunctionFsDevice::~FunctionFsDevice() {
  stop();
  if (ep0_ >= 0) ::close(ep0_);
}

void FunctionFsDevice::start(std::function<void(const BusEvent&)> on_event) {
  on_event_ = std::move(on_event);
  install_wake_handler();
  const RenumberedStrings fn = renumber_strings(function_);

  // Full speed only: the OpenFFBoard's STM32F407 has a full-speed PHY, and a function with no
  // high-speed descriptors keeps the gadget at full speed on any UDC.
  std::vector<std::uint8_t> head;
  put_le32(head, FUNCTIONFS_DESCRIPTORS_MAGIC_V2);
  put_le32(head, 0);  // length, set below
  put_le32(head, FUNCTIONFS_HAS_FS_DESC);
  put_le32(head, static_cast<std::uint32_t>(count_descriptors(fn.descriptors)));
  head.insert(head.end(), fn.descriptors.begin(), fn.descriptors.end());
  set_le32(head, 4, static_cast<std::uint32_t>(head.size()));
  if (::write(ep0_, head.data(), head.size()) != static_cast<ssize_t>(head.size()))
    fail("FunctionFS refused the descriptors (" + dir_ + "/ep0)");

  std::vector<std::uint8_t> strings;
  put_le32(strings, FUNCTIONFS_STRINGS_MAGIC);
  put_le32(strings, 0);
  put_le32(strings, static_cast<std::uint32_t>(fn.strings.size()));
  put_le32(strings, fn.strings.empty() ? 0 : 1);
  if (!fn.strings.empty()) {
    put_le16(strings, 0x0409);  // US English, the firmware's only language
    for (const std::string& s : fn.strings) {
      strings.insert(strings.end(), s.begin(), s.end());
      strings.push_back(0);
    }
  }
  set_le32(strings, 4, static_cast<std::uint32_t>(strings.size()));
  if (::write(ep0_, strings.data(), strings.size()) != static_cast<ssize_t>(strings.size()))
    fail("FunctionFS refused the strings (" + dir_ + "/ep0)");

  open_endpoints();
  ep0_thread_ = std::thread([this] { ep0_loop(); exited_[0].store(true); });
  out_thread_ = std::thread([this] { out_loop(); exited_[1].store(true); });
  in_thread_ = std::thread([this] { in_loop(); exited_[2].store(true); });
}

void FunctionFsDevice::stop() {
  if (stopping_.exchange(true)) return;
  std::thread* threads[] = {&ep0_thread_, &out_thread_, &in_thread_};
  for (int i = 0; i < 3; ++i) {
    if (!threads[i]->joinable()) continue;
    // A thread can be between its check of stopping_ and its next blocking call when the signal
    // comes: keep waking it until it says it has left.
    while (!exited_[i].load()) {
      pthread_kill(threads[i]->native_handle(), kWakeSignal);
      struct timespec pause {0, 200'000};
      nanosleep(&pause, nullptr);
    }
    threads[i]->join();
  }
  close_endpoints();
}

void FunctionFsDevice::open_endpoints() {
  // FunctionFS names the endpoint files ep1, ep2, ... in descriptor order: IN first for the
  // OpenFFBoard (0x83, then 0x02); the direction is taken from the descriptors, not assumed.
  const auto d = function_.function_descriptors();
  int index = 0;
  for (std::size_t at = 0; at + 2 <= d.size() && d[at] >= 2; at += d[at]) {
    if (d[at + 1] != 0x05) continue;
    ++index;
    const std::string path = dir_ + "/ep" + std::to_string(index);
    const bool in = (d[at + 2] & 0x80) != 0;
    const int fd = ::open(path.c_str(), in ? O_WRONLY : O_RDONLY);
    if (fd < 0) fail(path);
    (in ? ep_in_ : ep_out_).store(fd);
  }
}

void FunctionFsDevice::close_endpoints() {
  for (std::atomic<int>* fd : {&ep_in_, &ep_out_}) {
    const int old = fd->exchange(-1);
    if (old >= 0) ::close(old);
  }
}

// Events are read only once poll() says some are queued. A read of ep0 that waits for events
// sleeps holding FunctionFS's ffs->mutex (Linux 6.1 f_fs.c, ffs_ep0_read), and unbinding the
// gadget takes that mutex after queueing UNBIND (functionfs_unbind). A reader that took UNBIND
// and came back to wait before the unbinder reached the mutex held it against the unbinder for
// good: `echo "" > UDC` never returned (docs/USB_PID.md, item 18). poll() takes the mutex only
// for a moment.
void FunctionFsDevice::ep0_loop() {
  usb_functionfs_event events[4];
  while (!stopping_.load()) {
    pollfd ready{ep0_, POLLIN, 0};
    const int polled = ::poll(&ready, 1, 100);
    if (polled < 0 && errno != EINTR) return;
    if (polled <= 0 || !(ready.revents & POLLIN)) continue;
    const ssize_t n = ::read(ep0_, events, sizeof events);
    if (n < 0) {
      // EIDRM: the host began another control transfer (or left) before this one was answered;
      // FunctionFS dropped it, and the next read gives the events that followed.
      if (errno == EINTR || errno == EAGAIN || errno == EIDRM) continue;
      return;
    }
    for (ssize_t i = 0; i < n / static_cast<ssize_t>(sizeof events[0]); ++i) {
      const usb_functionfs_event& e = events[i];
      BusEvent event{BusEvent::Kind::Bind, {}};
      switch (e.type) {
        case FUNCTIONFS_BIND: event.kind = BusEvent::Kind::Bind; break;
        case FUNCTIONFS_UNBIND: event.kind = BusEvent::Kind::Unbind; break;
        case FUNCTIONFS_ENABLE:
          event.kind = BusEvent::Kind::Enable;
          enabled_.store(true);
          function_.configured();
          break;
        case FUNCTIONFS_DISABLE:
          event.kind = BusEvent::Kind::Disable;
          enabled_.store(false);
          function_.deconfigured();
          break;
        case FUNCTIONFS_SUSPEND: event.kind = BusEvent::Kind::Suspend; function_.suspended(true); break;
        case FUNCTIONFS_RESUME: event.kind = BusEvent::Kind::Resume; function_.suspended(false); break;
        case FUNCTIONFS_SETUP: {
          event.kind = BusEvent::Kind::Setup;
          event.setup = SetupPacket{e.u.setup.bRequestType, e.u.setup.bRequest, le16toh(e.u.setup.wValue),
                                    le16toh(e.u.setup.wIndex), le16toh(e.u.setup.wLength)};
          handle_setup(event.setup);
          break;
        }
        default: continue;
      }
      if (on_event_) on_event_(event);
    }
  }
}

void FunctionFsDevice::handle_setup(const SetupPacket& setup) {
  // FunctionFS ends a control transfer by the direction of the next ep0 call: data in the
  // request's direction completes it, a call against it stalls it (functionfs.rst).
  auto stall = [&] {
    if (setup.device_to_host()) {
      [[maybe_unused]] ssize_t r = ::read(ep0_, nullptr, 0);
    } else {
      [[maybe_unused]] ssize_t r = ::write(ep0_, nullptr, 0);
    }
    if (on_event_) on_event_(BusEvent{BusEvent::Kind::Stalled, setup});
  };
  if (!function_.accepts(setup)) return stall();
  if (setup.device_to_host()) {
    ControlReply reply = function_.control(setup, {});
    if (reply.stall) return stall();
    if (reply.data.size() > setup.wLength) reply.data.resize(setup.wLength);
    [[maybe_unused]] ssize_t r = ::write(ep0_, reply.data.data(), reply.data.size());
    return;
  }
  std::vector<std::uint8_t> data(setup.wLength);
  if (setup.wLength == 0) {
    const ControlReply reply = function_.control(setup, {});
    if (reply.stall) return stall();
    [[maybe_unused]] ssize_t r = ::read(ep0_, nullptr, 0);
    return;
  }
  // The data stage must be read before the function can see it; FunctionFS acknowledges the
  // status stage with that read, so a refusal after it can no longer stall.
  const ssize_t got = ::read(ep0_, data.data(), data.size());
  if (got < 0) return;
  data.resize(static_cast<std::size_t>(got));
  (void)function_.control(setup, data);
}

void FunctionFsDevice::out_loop() {
  std::uint8_t buffer[64];
  while (!stopping_.load()) {
    const int fd = ep_out_.load();
    if (fd < 0) return;
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0) continue;  // EINTR at stop, ESHUTDOWN while the host has the function disabled
    out_transfers_.fetch_add(1, std::memory_order_relaxed);
    function_.interrupt_out(std::span<const std::uint8_t>(buffer, static_cast<std::size_t>(n)));
  }
}

void FunctionFsDevice::in_loop() {
  std::vector<std::uint8_t> report;
  report.reserve(64);
  while (!stopping_.load()) {
    if (!function_.next_interrupt_in(report, std::chrono::milliseconds(10))) continue;
    const int fd = ep_in_.load();
    if (fd < 0) return;
    // The write returns once the host's interrupt IN poll took the report: the host's bInterval
    // paces this loop, as the USB peripheral paces the firmware.
    const ssize_t n = ::write(fd, report.data(), report.size());
    const bool delivered = n == static_cast<ssize_t>(report.size());
    if (delivered) in_transfers_.fetch_add(1, std::memory_order_relaxed);
    function_.interrupt_in_done(delivered);
  }
}

}  // namespace sandpaper::usb_lab
