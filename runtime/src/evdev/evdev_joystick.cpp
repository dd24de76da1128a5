// The input-event-node driver: open and give back on the caller's thread, updates and events on
// the I/O thread, single-slot atomics between it and the tick (docs/DEVICES.md).
#include "sandpaper/runtime/evdev/evdev_joystick.hpp"

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <linux/input.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>
#include <vector>

#include "sandpaper/runtime/device_limits.hpp"
#include "sandpaper/runtime/usb/hid_descriptor.hpp"

namespace sandpaper::runtime::evdev {
namespace {

std::int64_t monotonic_ns() noexcept {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return std::int64_t{t.tv_sec} * 1'000'000'000 + t.tv_nsec;
}

std::uint64_t pack_position(glm::dvec2 p) noexcept {
  return (std::uint64_t{std::bit_cast<std::uint32_t>(static_cast<float>(p.y))} << 32) |
         std::bit_cast<std::uint32_t>(static_cast<float>(p.x));
}
glm::dvec2 unpack_position(std::uint64_t v) noexcept {
  return {std::bit_cast<float>(static_cast<std::uint32_t>(v)), std::bit_cast<float>(static_cast<std::uint32_t>(v >> 32))};
}
std::uint32_t pack_levels(std::int16_t x, std::int16_t y) noexcept {
  return (std::uint32_t{static_cast<std::uint16_t>(y)} << 16) | static_cast<std::uint16_t>(x);
}
std::int16_t level_in(std::uint32_t packed, int axis) noexcept {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(axis == 0 ? packed : packed >> 16));
}

// The direction of each axis's effect (Documentation/input/ff.rst: 0x4000 pushes left, 0x8000 up in
// the kernel's words). hid-pidff rescales it onto the device's Direction range with Direction Enable
// set, and the OpenFFBoard applies sin(direction) to X and -cos(direction) to Y (HidFFB.cpp, 160af91):
// 0x4000 gives X alone, 0x8000 Y alone, each with factor +1, as the HID PID driver's per-axis
// effects do, so one calibration's command_sense holds on both paths.
constexpr std::uint16_t kDirection[2] = {0x4000, 0x8000};

// The report descriptor's Magnitude range of Set Constant Force (HID PID 1.0 section 5.9).
bool magnitude_range(const std::string& descriptor_file, std::int32_t& lo, std::int32_t& hi, std::string& why) {
  std::ifstream in(descriptor_file, std::ios::binary);
  const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (bytes.empty()) {
    why = "cannot read the HID report descriptor " + descriptor_file;
    return false;
  }
  try {
    const auto d = usb::parse_hid_report_descriptor(bytes);
    const usb::HidField* f = d.find(usb::ReportType::Output, usb::pid::kSetConstantForceReport, usb::pid::kMagnitude);
    if (f == nullptr || f->logical_min >= 0 || f->logical_max <= 0) {
      why = "the HID report descriptor has no signed Magnitude in a Set Constant Force report";
      return false;
    }
    lo = f->logical_min;
    hi = f->logical_max;
    return true;
  } catch (const usb::HidDescriptorError& e) {
    why = std::string("the HID report descriptor cannot be parsed: ") + e.what();
    return false;
  }
}

std::string errno_text(int e) {
  const char* name = e == ENODEV ? "ENODEV" : e == EACCES ? "EACCES" : e == EPERM ? "EPERM" : e == ENOENT ? "ENOENT"
                   : e == ENOSPC ? "ENOSPC" : e == EINVAL ? "EINVAL" : e == EIO ? "EIO" : nullptr;
  return (name ? std::string(name) + ": " : std::string()) + std::strerror(e);
}

}  // namespace

std::int16_t level_for_command(std::int32_t command, std::int32_t logical_min, std::int32_t logical_max) noexcept {
  if (logical_min >= 0 || logical_max <= 0) return 0;
  const std::int64_t c = std::clamp<std::int64_t>(command, logical_min, logical_max);
  // The smallest level whose truncated rescale reaches `c`: each level step moves the result by
  // max/0x7fff (or min/-0x8000) <= 1, so every command has one.
  if (c > 0) return static_cast<std::int16_t>(std::min<std::int64_t>((c * 0x7fff + logical_max - 1) / logical_max, 0x7fff));
  if (c < 0) {
    const std::int64_t m = -std::int64_t{logical_min};
    return static_cast<std::int16_t>(-std::min<std::int64_t>((-c * 0x8000 + m - 1) / m, 0x8000));
  }
  return 0;
}

std::int32_t command_for_level(std::int16_t level, std::int32_t logical_min, std::int32_t logical_max) noexcept {
  const std::int64_t i = level;
  if (i == 0) return 0;
  return static_cast<std::int32_t>(i > 0 ? i * logical_max / 0x7fff : i * logical_min / -0x8000);
}

EvdevJoystick::EvdevJoystick(const EvdevNode& node, const calibration::DeviceCalibration& calibration)
    : node_(node), calibration_(calibration), limits_(limits_of(calibration)) {
  if (const double interval_s = std::max(calibration.usb_out_interval_s, node.out_interval_s); interval_s > 0)
    out_interval_ns_ = static_cast<std::int64_t>(interval_s * 1e9);
  levels_ = calibration.command_unit == kLevelUnit;
  std::string why;
  if (levels_) {
    magnitude_min_ = -0x7fff;  // levels as they are: struct ff_constant_effect's range, symmetric
    magnitude_max_ = 0x7fff;
  } else if (node.report_descriptor.empty() || !magnitude_range(node.report_descriptor, magnitude_min_, magnitude_max_, why))
    fail(0, node.report_descriptor.empty() ? "its driver is not HID (no report descriptor in sysfs): its calibration "
                                             "file must count levels (command_unit = \"FF_CONSTANT level\")"
                                           : why);
  fd_ = ::open(node.path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) fail(errno, "cannot open it");
  if (const int rc = libevdev_new_from_fd(fd_, &dev_); rc < 0) fail(-rc, "libevdev cannot read it");
  if (!libevdev_has_event_code(dev_, EV_FF, FF_CONSTANT)) fail(0, "it has no constant-force effect (FF_CONSTANT)");
  const unsigned first = libevdev_has_event_code(dev_, EV_ABS, ABS_X) ? ABS_X : ABS_WHEEL;
  if (!libevdev_has_event_code(dev_, EV_ABS, first)) fail(0, "it has no ABS_X (or ABS_WHEEL) axis");
  abs_code_[0] = first;
  axes_ = 1;
  // A wheel's device file ([wheel]) plays one axis, though its gamepad report has a Y as well.
  if (first == ABS_X && libevdev_has_event_code(dev_, EV_ABS, ABS_Y) && !calibration_.wheel()) {
    abs_code_[1] = ABS_Y;
    axes_ = 2;
  }
  for (int a = 0; a < axes_; ++a) {
    const input_absinfo* info = libevdev_get_abs_info(dev_, abs_code_[a]);
    abs_min_[a] = info->minimum;
    abs_max_[a] = info->maximum;
    abs_fuzz_[a] = info->fuzz;
  }
  // hid-input gives joystick axes a fuzz of 1/256 of their range, and the input core then averages
  // or drops small moves (input_defuzz_abs_event): 0.4 mm on a 100 mm workspace. The texture needs them.
  for (int a = 0; a < axes_; ++a) {
    input_absinfo info = *libevdev_get_abs_info(dev_, abs_code_[a]);
    if (info.fuzz == 0) continue;
    info.fuzz = 0;
    if (libevdev_kernel_set_abs_info(dev_, abs_code_[a], &info) == 0) fuzz_set_ = true;
  }
  if (libevdev_has_event_code(dev_, EV_FF, FF_GAIN)) {
    if (!write_ff(FF_GAIN, 0xFFFF)) fail(errno, "cannot set its gain (FF_GAIN)");
    gain_set_ = true;
  }
  if (libevdev_has_event_code(dev_, EV_FF, FF_AUTOCENTER)) {
    if (!write_ff(FF_AUTOCENTER, 0)) fail(errno, "cannot turn its autocenter off (FF_AUTOCENTER)");
    autocenter_set_ = true;
  }
  for (int a = 0; a < axes_; ++a) {
    ff_effect e{};
    e.type = FF_CONSTANT;
    e.id = -1;
    e.direction = kDirection[a];
    e.replay.length = 0;  // infinite
    if (ioctl(fd_, EVIOCSFF, &e) < 0) fail(errno, "cannot upload a constant-force effect (EVIOCSFF)");
    effect_id_[a] = e.id;
    if (!write_ff(static_cast<unsigned>(e.id), 1)) fail(errno, "cannot start its effect");
  }
  position_raw_.store(pack_position(current_position()), std::memory_order_release);
  io_running_.store(true, std::memory_order_release);
  try {
    io_thread_ = std::thread([this] { io_thread_body(); });
  } catch (...) {
    io_running_.store(false);
    fail(0, "cannot start its I/O thread");
  }
}

EvdevJoystick::~EvdevJoystick() { close_nonrt(); }

void EvdevJoystick::fail(int error, const std::string& what) {
  close_nonrt();
  throw EvdevError(error, what + (error ? " (" + errno_text(error) + ")" : std::string()));
}

bool EvdevJoystick::write_ff(unsigned code, int value) noexcept {
  input_event ev{};
  ev.type = EV_FF;
  ev.code = static_cast<std::uint16_t>(code);
  ev.value = value;
  return ::write(fd_, &ev, sizeof ev) == static_cast<ssize_t>(sizeof ev);
}

void EvdevJoystick::set_fault(DeviceFault fault, int error) noexcept {
  DeviceFault none = DeviceFault::None;
  if (fault_.compare_exchange_strong(none, fault, std::memory_order_acq_rel)) fault_errno_.store(error, std::memory_order_release);
}

std::string EvdevJoystick::fault_detail_nonrt() const {
  if (last_fault_rt() == DeviceFault::None) return {};
  const int e = fault_errno_.load(std::memory_order_acquire);
  return e ? errno_text(e) : std::string("the I/O thread stopped cycling");
}

// The axes' values as libevdev holds them, mapped from their absinfo range onto the workspace
// (centre 0), as the HID PID driver maps its input report's logical ranges.
glm::dvec2 EvdevJoystick::current_position() const noexcept {
  glm::dvec2 p{0, 0};
  for (int a = 0; a < axes_; ++a) {
    const double centre = 0.5 * (double(abs_min_[a]) + abs_max_[a]), half = 0.5 * (double(abs_max_[a]) - abs_min_[a]);
    p[a] = half > 0 ? (libevdev_get_event_value(dev_, EV_ABS, abs_code_[a]) - centre) / half * 0.5 *
                          calibration_.workspace_size_m[a]
                    : 0.0;
  }
  return p;
}

// Every event queued; positions published at each SYN_REPORT. After a SYN_DROPPED libevdev replays
// the device's state as sync events, which end in a SYN_REPORT too.
bool EvdevJoystick::drain_events() noexcept {
  bool fresh = false;
  unsigned flags = LIBEVDEV_READ_FLAG_NORMAL;
  for (;;) {
    input_event ev{};
    const int rc = libevdev_next_event(dev_, flags, &ev);
    if (rc == -EAGAIN) {
      if (flags == LIBEVDEV_READ_FLAG_SYNC) {
        flags = LIBEVDEV_READ_FLAG_NORMAL;
        continue;
      }
      break;
    }
    if (rc < 0) {
      set_fault(rc == -ENODEV ? DeviceFault::Unplugged : DeviceFault::ReadFailed, -rc);
      return false;
    }
    if (rc == LIBEVDEV_READ_STATUS_SYNC) flags = LIBEVDEV_READ_FLAG_SYNC;
    if (ev.type == EV_SYN && ev.code == SYN_REPORT) fresh = true;
  }
  if (fresh) {
    position_raw_.store(pack_position(current_position()), std::memory_order_relaxed);
    position_reports_.fetch_add(1, std::memory_order_release);
  }
  return true;
}

bool EvdevJoystick::update_level(int axis, std::int16_t level) noexcept {
  const auto a = static_cast<std::size_t>(axis);
  ff_effect e{};
  e.type = FF_CONSTANT;
  e.id = static_cast<std::int16_t>(effect_id_[a]);
  e.direction = kDirection[a];
  e.u.constant.level = level;
  if (ioctl(fd_, EVIOCSFF, &e) < 0) return false;
  sent_level_[a].store(level, std::memory_order_relaxed);
  updates_[a].fetch_add(1, std::memory_order_relaxed);
  return true;
}

// Cycles once per out_interval: the events that came (waiting for them until the cycle's end),
// then at most one level update, the changed axes in turn. hid-pidff queues the Set Constant Force
// it makes of an update in usbhid's FIFO, which sends one report per frame of the interrupt OUT
// endpoint: one update per bInterval keeps the FIFO from filling ("output queue full").
void EvdevJoystick::io_thread_body() noexcept {
  std::int64_t next = monotonic_ns() + out_interval_ns_;
  int turn = 0;
  while (io_running_.load(std::memory_order_acquire)) {
    for (;;) {
      const std::int64_t left = next - monotonic_ns();
      if (left <= 0) break;
      pollfd p{fd_, POLLIN, 0};
      timespec wait{static_cast<time_t>(left / 1'000'000'000), static_cast<long>(left % 1'000'000'000)};
      const int ready = ppoll(&p, 1, &wait, nullptr);
      if (ready > 0 && !drain_events()) return;
      if (ready > 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL)) && !(p.revents & POLLIN)) {
        set_fault(DeviceFault::Unplugged, ENODEV);
        return;
      }
    }
    if (!drain_events()) return;
    const std::uint32_t want = level_raw_.load(std::memory_order_acquire);
    for (int k = 0; k < axes_; ++k) {
      const int axis = (turn + k) % axes_;
      const std::int16_t level = level_in(want, axis);
      if (level == sent_level_[static_cast<std::size_t>(axis)].load(std::memory_order_relaxed)) continue;
      if (!update_level(axis, level)) {
        const int e = errno;
        set_fault(e == ENODEV ? DeviceFault::Unplugged : DeviceFault::WriteFailed, e);
        return;
      }
      turn = axis + 1;
      break;
    }
    io_cycles_.fetch_add(1, std::memory_order_release);
    next += out_interval_ns_;
    if (const std::int64_t now = monotonic_ns(); next < now) next = now;  // behind: carry on, do not burst
  }
}

namespace {
// level_for_force once the unit is known: the tick passes what the constructor decided, so it does
// no string comparison of its own.
std::int16_t level_in(const calibration::DeviceCalibration& calibration, bool levels, int axis, double force_N,
                      std::int32_t magnitude_min, std::int32_t magnitude_max) noexcept {
  if (levels) {
    magnitude_min = -0x7fff;
    magnitude_max = 0x7fff;
  }
  const auto& scale = calibration.axis_scale(axis);
  double units = scale.command_sense * scale.command(force_N);
  if (!std::isfinite(units)) units = 0;
  double lowest = magnitude_min, highest = magnitude_max;
  if (calibration.command_max > 0) {
    lowest = std::max(lowest, -static_cast<double>(calibration.command_max));
    highest = std::min(highest, static_cast<double>(calibration.command_max));
  }
  const auto command = static_cast<std::int32_t>(std::clamp(std::round(units), lowest, highest));
  if (levels) return static_cast<std::int16_t>(command);
  return level_for_command(command, magnitude_min, magnitude_max);
}
}  // namespace

std::int16_t level_for_force(const calibration::DeviceCalibration& calibration, int axis, double force_N,
                             std::int32_t magnitude_min, std::int32_t magnitude_max) noexcept {
  return level_in(calibration, calibration.command_unit == kLevelUnit, axis, force_N, magnitude_min, magnitude_max);
}

std::int16_t EvdevJoystick::level_of(int axis, double force_N) const noexcept {
  return level_in(calibration_, levels_, axis, force_N, magnitude_min_, magnitude_max_);
}

bool EvdevJoystick::write_force_rt(glm::dvec2 force_N) noexcept {
  const std::int16_t x = level_of(0, force_N.x), y = axes_ > 1 ? level_of(1, force_N.y) : std::int16_t{0};
  level_raw_.store(pack_levels(x, y), std::memory_order_release);
  return fault_.load(std::memory_order_acquire) == DeviceFault::None;
}

// An I/O thread that has not cycled for this long (50 out_intervals at 1 ms) is stuck.
constexpr double kStuckS = 0.05;

bool EvdevJoystick::read_position_rt(double t_s, glm::dvec2& position_m) noexcept {
  if (fault_.load(std::memory_order_acquire) != DeviceFault::None) return false;
  const std::uint64_t reports = position_reports_.load(std::memory_order_acquire);
  fresh_ = reports != seen_reports_;
  seen_reports_ = reports;
  position_m_ = unpack_position(position_raw_.load(std::memory_order_relaxed));
  const std::uint64_t cycles = io_cycles_.load(std::memory_order_acquire);
  if (cycles != seen_cycles_ || !have_time_) {
    seen_cycles_ = cycles;
    last_cycle_t_s_ = t_s;
    have_time_ = true;
  }
  if (t_s - last_cycle_t_s_ > kStuckS) {
    set_fault(DeviceFault::ReadTimedOut, 0);
    return false;
  }
  position_m = position_m_;
  return true;
}

void EvdevJoystick::close_nonrt() noexcept {
  if (closed_) return;
  closed_ = true;
  io_running_.store(false, std::memory_order_release);
  if (io_thread_.joinable()) io_thread_.join();
  if (fd_ >= 0) {
    // Each step whatever the last returned: on a node that has gone they all fail at once.
    for (int a = 0; a < 2; ++a)
      if (effect_id_[a] >= 0) {
        update_level(a, 0);
        write_ff(static_cast<unsigned>(effect_id_[a]), 0);
        ioctl(fd_, EVIOCRMFF, effect_id_[a]);
        effect_id_[a] = -1;
      }
    if (autocenter_set_) write_ff(FF_AUTOCENTER, 0xFFFF);
    if (gain_set_) write_ff(FF_GAIN, 0xFFFF);
    if (fuzz_set_ && dev_ != nullptr)
      for (int a = 0; a < axes_; ++a) {
        input_absinfo info = *libevdev_get_abs_info(dev_, abs_code_[a]);
        info.fuzz = abs_fuzz_[a];
        libevdev_kernel_set_abs_info(dev_, abs_code_[a], &info);
      }
  }
  if (dev_ != nullptr) libevdev_free(dev_);
  dev_ = nullptr;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

}  // namespace sandpaper::runtime::evdev
