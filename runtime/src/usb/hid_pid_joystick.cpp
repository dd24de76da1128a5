// The HID PID driver's tick, I/O thread and shutdown (docs/USB_PID.md lists them report by report);
// the open sequence is hid_pid_open.cpp.
#include "sandpaper/runtime/usb/hid_pid_joystick.hpp"

#include "hid_pid_internal.hpp"
#include "sandpaper/runtime/device_limits.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <ctime>
#include <string>
#include <vector>

namespace sandpaper::runtime::usb {
namespace {

// Two 32-bit values in one lock-free atomic word: the single-slot exchange of the tick and the I/O thread.
std::uint64_t pack(std::uint32_t x, std::uint32_t y) noexcept { return (std::uint64_t{y} << 32) | x; }
std::uint32_t low(std::uint64_t v) noexcept { return static_cast<std::uint32_t>(v & 0xFFFFFFFFu); }
std::uint32_t high(std::uint64_t v) noexcept { return static_cast<std::uint32_t>(v >> 32); }
// Positions travel as float metres: 4 nm resolution over the +-50 mm of a joystick, far below its
// 16-bit report steps.
std::uint64_t pack_position(glm::dvec2 p) noexcept {
  return pack(std::bit_cast<std::uint32_t>(static_cast<float>(p.x)), std::bit_cast<std::uint32_t>(static_cast<float>(p.y)));
}
glm::dvec2 unpack_position(std::uint64_t v) noexcept {
  return {std::bit_cast<float>(low(v)), std::bit_cast<float>(high(v))};
}

}  // namespace

const char* to_string(DeviceFault fault) noexcept {
  switch (fault) {
    case DeviceFault::None: return "none";
    case DeviceFault::ReadTimedOut: return "device read timed out";
    case DeviceFault::ReadFailed: return "device read failed";
    case DeviceFault::WriteFailed: return "device write failed";
    case DeviceFault::Unplugged: return "device unplugged";
  }
  return "none";
}

// A device that reports every poll (1 ms at full speed) and has said nothing for 50 ms is gone
// quiet; that is the watchdog's limit unless the device resends unchanged reports less often.
constexpr double kDefaultStaleLimitS = 0.05;

HidPidJoystick::HidPidJoystick(UsbTransport& transport, const calibration::DeviceCalibration& calibration,
                               HidPidOptions options)
    : transport_(transport), calibration_(calibration), options_(options), limits_(limits_of(calibration)) {
  if (options_.stale_limit_s <= 0)
    options_.stale_limit_s = std::max(kDefaultStaleLimitS, 2 * calibration.usb_idle_report_period_s);
  open();
  position_raw_.store(pack_position(position_m_), std::memory_order_release);
  if (options_.io == HidPidIo::IoThread) start_io_thread();
}

HidPidJoystick::~HidPidJoystick() { close(); }

DeviceFault HidPidJoystick::last_fault_rt() const noexcept { return fault_.load(std::memory_order_acquire); }
std::string HidPidJoystick::fault_detail_nonrt() const {
  return fault() == DeviceFault::None ? std::string() : std::string(to_string(fault_status()));
}
UsbStatus HidPidJoystick::fault_status() const noexcept { return fault_status_.load(std::memory_order_acquire); }
std::array<std::int32_t, 2> HidPidJoystick::last_command() const noexcept {
  return {last_command_[0].load(std::memory_order_relaxed), last_command_[1].load(std::memory_order_relaxed)};
}

void HidPidJoystick::set_fault(DeviceFault fault, UsbStatus status) noexcept {
  // The first fault is the cause; later ones (the zero force failing after an unplug) are consequences.
  DeviceFault none = DeviceFault::None;
  if (fault_.compare_exchange_strong(none, fault, std::memory_order_acq_rel))
    fault_status_.store(status, std::memory_order_release);
}

void HidPidJoystick::start_io_thread() {
  io_running_.store(true, std::memory_order_release);
  try {
    io_thread_ = std::thread([this] { io_thread_body(); });
  } catch (...) {
    io_running_.store(false);
    fail_open(UsbStatus::Other, "cannot start the USB I/O thread");
  }
}

void HidPidJoystick::stop_io_thread() noexcept {
  io_running_.store(false, std::memory_order_release);
  if (io_thread_.joinable()) io_thread_.join();
}

// The I/O thread: the input reports that arrived (a 1 kHz interrupt endpoint paces them), then the
// latest force if the tick published a new one, at most once per device period. A force transfer that times out is
// sent again (with the latest force) next cycle; only stale_limit_s without one is a fault. It may block in a transfer for as
// long as libusb's timeout; the tick then sees no new position and the watchdog (stale_limit_s)
// stops the servo loop, which publishes zero force; the shutdown sequence sends it.
void HidPidJoystick::io_thread_body() noexcept {
  const auto period_ns = static_cast<std::int64_t>(1e9 / std::max(1.0, limits_.max_rate_hz));
  std::int64_t next = monotonic_ns();
  std::int64_t last_write_ns = next;  // the last time every changed axis's force went out
  std::int32_t sent[2] = {last_command_[0].load(std::memory_order_relaxed),  // what the device has (open sent 0)
                          last_command_[1].load(std::memory_order_relaxed)};
  while (io_running_.load(std::memory_order_acquire)) {
    // Every report that has arrived, without waiting: the transport keeps an IN transfer in flight,
    // so waiting here would only hold back the force. The tick wants the latest position, not the
    // oldest one queued (PID State reports may come between).
    bool fresh = false;
    for (int attempt = 0; attempt < kReadsPerTick; ++attempt) {
      std::size_t length = 0;
      const UsbStatus s = transport_.read_input(input_, length, 0);
      if (s == UsbStatus::Timeout) break;
      if (s != UsbStatus::Ok) {
        set_fault(s == UsbStatus::NoDevice ? DeviceFault::Unplugged : DeviceFault::ReadFailed, s);
        return;
      }
      glm::dvec2 p{0, 0};
      if (decode_position({input_.data(), length}, p)) {
        position_raw_.store(pack_position(p), std::memory_order_relaxed);
        fresh = true;
      }
    }
    if (fresh) position_reports_.fetch_add(1, std::memory_order_release);
    const std::uint64_t published = command_published_.load(std::memory_order_acquire);
    if (published != command_sent_.load(std::memory_order_relaxed)) {
      const std::uint64_t command = command_raw_.load(std::memory_order_relaxed);
      const std::int32_t want[2] = {static_cast<std::int32_t>(low(command)), static_cast<std::int32_t>(high(command))};
      // Only an axis whose magnitude changed: a full-speed interrupt OUT endpoint moves one report
      // per frame, so an axis held constant (Y while a texture is scanned along X) leaves every
      // frame to the other.
      bool all_sent = true;
      for (int axis = 0; axis < axes_; ++axis) {
        const auto a = static_cast<std::size_t>(axis);
        if (want[a] == sent[a]) continue;
        const UsbStatus st = write_constant_force(axis, want[a]);
        if (st == UsbStatus::Ok) {
          sent[a] = want[a];
        } else if (st == UsbStatus::Timeout) {
          all_sent = false;  // the device NAKed it past the timeout: the latest goes out next cycle
        } else {
          set_fault(st == UsbStatus::NoDevice ? DeviceFault::Unplugged : DeviceFault::WriteFailed, st);
          return;
        }
      }
      const std::int64_t now = monotonic_ns();
      if (all_sent) {
        command_sent_.store(published, std::memory_order_release);
        last_write_ns = now;
      } else if (static_cast<double>(now - last_write_ns) * 1e-9 > options_.stale_limit_s) {
        // A device that takes no force for as long as the position watchdog allows is gone quiet.
        set_fault(DeviceFault::WriteFailed, UsbStatus::Timeout);
        return;
      }
    }
    io_cycles_.fetch_add(1, std::memory_order_release);
    next += period_ns;
    const std::int64_t now = monotonic_ns();
    if (next < now) next = now;  // behind (a slow transfer): carry on from now, do not burst
    timespec wake{};
    wake.tv_sec = static_cast<time_t>(next / 1'000'000'000);
    wake.tv_nsec = static_cast<long>(next % 1'000'000'000);
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr);
  }
}

bool HidPidJoystick::flush_nonrt(double timeout_s) {
  if (options_.io != HidPidIo::IoThread || !io_thread_.joinable()) return true;
  const std::uint64_t published = command_published_.load(std::memory_order_acquire);
  const std::uint64_t cycles = io_cycles_.load(std::memory_order_acquire) + 2;
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < until) {
    if (fault_.load(std::memory_order_acquire) != DeviceFault::None) return false;
    if (command_sent_.load(std::memory_order_acquire) >= published && io_cycles_.load(std::memory_order_acquire) >= cycles)
      return true;
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
  return false;
}

UsbStatus HidPidJoystick::write_constant_force(int axis, std::int32_t magnitude) noexcept {
  const auto a = static_cast<std::size_t>(axis);
  write_field(cf_report_[a], ids_, magnitude_, magnitude);
  const UsbStatus s = transport_.write_output({cf_report_[a].data(), cf_bytes_});
  if (s == UsbStatus::Ok) last_command_[a].store(magnitude, std::memory_order_relaxed);
  return s;
}

bool HidPidJoystick::send_constant_force(int axis, std::int32_t magnitude) noexcept {
  const UsbStatus s = write_constant_force(axis, magnitude);
  if (s == UsbStatus::Ok) return true;
  set_fault(s == UsbStatus::NoDevice ? DeviceFault::Unplugged : DeviceFault::WriteFailed, s);
  return false;
}

std::int32_t HidPidJoystick::command_of(int axis, double force_N) const noexcept {
  const auto& scale = calibration_.axis_scale(axis);
  double units = scale.command_sense * scale.command(force_N);
  if (!std::isfinite(units)) units = 0;
  double lowest = magnitude_.logical_min, highest = magnitude_.logical_max;
  if (calibration_.command_max > 0) {
    lowest = std::max(lowest, -static_cast<double>(calibration_.command_max));
    highest = std::min(highest, static_cast<double>(calibration_.command_max));
  }
  return static_cast<std::int32_t>(std::clamp(std::round(units), lowest, highest));
}

bool HidPidJoystick::write_force_rt(glm::dvec2 force_N) noexcept {
  const std::int32_t x = command_of(0, force_N.x), y = command_of(1, force_N.y);
  if (options_.io == HidPidIo::IoThread) {
    command_raw_.store(pack(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y)), std::memory_order_relaxed);
    command_published_.fetch_add(1, std::memory_order_release);
    return fault_.load(std::memory_order_acquire) == DeviceFault::None;
  }
  // Both axes are sent even if the first failed: the other may still carry the zero.
  const bool ok = send_constant_force(0, x);
  return (axes_ == 1 || send_constant_force(1, y)) && ok;
}

bool HidPidJoystick::decode_position(std::span<const std::uint8_t> report, glm::dvec2& position_m) const noexcept {
  if (ids_ && (report.empty() || report[0] != x_.report_id)) return false;
  const std::size_t need = descriptor_.report_bytes(ReportType::Input, x_.report_id);
  if (report.size() < need) return false;
  const HidField* axes[2] = {&x_, &y_};
  position_m[1] = 0;  // a wheel's only axis is x
  for (int a = 0; a < axes_; ++a) {
    const HidField& f = *axes[a];
    const double centre = 0.5 * (static_cast<double>(f.logical_min) + f.logical_max);
    const double half = 0.5 * (static_cast<double>(f.logical_max) - f.logical_min);
    const double v = static_cast<double>(read_field(report, ids_, f));
    position_m[a] = half > 0 ? (v - centre) / half * 0.5 * calibration_.workspace_size_m[a] : 0.0;
  }
  return true;
}

bool HidPidJoystick::read_position_rt(double t_s, glm::dvec2& position_m) noexcept {
  bool fresh = false;
  if (options_.io == HidPidIo::IoThread) {
    if (fault_.load(std::memory_order_acquire) != DeviceFault::None) return false;
    const std::uint64_t reports = position_reports_.load(std::memory_order_acquire);
    fresh = reports != seen_reports_;
    seen_reports_ = reports;
    position_m_ = unpack_position(position_raw_.load(std::memory_order_relaxed));
  } else {
    for (int attempt = 0; attempt < kReadsPerTick && !fresh; ++attempt) {
      std::size_t length = 0;
      const UsbStatus s = transport_.read_input(input_, length, options_.read_timeout_ms);
      if (s == UsbStatus::Timeout) break;
      if (s != UsbStatus::Ok) {
        set_fault(s == UsbStatus::NoDevice ? DeviceFault::Unplugged : DeviceFault::ReadFailed, s);
        return false;
      }
      fresh = decode_position({input_.data(), length}, position_m_);  // else another report (PID State): read on
    }
  }
  if (fresh || !have_time_) {
    last_report_t_s_ = t_s;
    have_time_ = true;
  }
  // The watchdog: no position for stale_limit_s of servo time, whether the device went quiet or
  // the I/O thread is stuck in a transfer. The loop then commands zero and stops.
  if (t_s - last_report_t_s_ > options_.stale_limit_s) {
    set_fault(DeviceFault::ReadTimedOut, UsbStatus::Timeout);
    return false;
  }
  fresh_ = fresh;
  position_m = position_m_;
  return true;
}

void HidPidJoystick::close() noexcept {
  if (closed_) return;
  closed_ = true;
  // From here the transport is used by this thread alone.
  stop_io_thread();
  // Each report of the sequence is sent again while the device NAKs it past the transfer's
  // timeout, all of them within close_timeout_ms; a device that is gone fails them at once.
  close_deadline_ns_ = monotonic_ns() + std::int64_t{options_.close_timeout_ms} * 1'000'000;
  try {
    for (std::size_t a = 0; a < 2; ++a)
      if (block_index_[a]) {
        write_field(cf_report_[a], ids_, magnitude_, 0);
        if (write_open({cf_report_[a].data(), cf_bytes_}) == UsbStatus::Ok) last_command_[a].store(0, std::memory_order_relaxed);
      }
    const HidField* op_index = descriptor_.find(ReportType::Output, pid::kEffectOperationReport, pid::kEffectBlockIndex);
    const HidField* op = descriptor_.find(ReportType::Output, pid::kEffectOperationReport, pid::kEffectOperation);
    for (std::size_t a = 0; a < 2; ++a)
      if (started_[a] && op_index && op && op->array_value(pid::kOpEffectStop)) {
        Buffer b{};
        b[0] = op->report_id;
        write_field(b, ids_, *op_index, block_index_[a]);
        write_field(b, ids_, *op, *op->array_value(pid::kOpEffectStop));
        if (const HidField* f = descriptor_.find(ReportType::Output, pid::kEffectOperationReport, pid::kLoopCount))
          write_field(b, ids_, *f, 0);
        write_open(report(b, descriptor_.report_bytes(ReportType::Output, op->report_id)));
        started_[a] = false;
      }
    if (const HidField* free_index = descriptor_.find(ReportType::Output, pid::kBlockFreeReport, pid::kEffectBlockIndex))
      for (std::size_t a = 0; a < 2; ++a)
        if (block_index_[a]) {
          Buffer b{};
          b[0] = free_index->report_id;
          write_field(b, ids_, *free_index, block_index_[a]);
          write_open(report(b, descriptor_.report_bytes(ReportType::Output, free_index->report_id)));
        }
    block_index_ = {0, 0};
    if (actuators_enabled_) {
      device_control(pid::kDcStopAllEffects);
      device_control(pid::kDcDisableActuators);
      actuators_enabled_ = false;
    }
  } catch (...) {
    // Building a report cannot throw; nothing above may stop the interface from being given back.
  }
  if (claimed_) transport_.release_interface();
  claimed_ = false;
  if (detached_) transport_.attach_kernel_driver();
  detached_ = false;
}

}  // namespace sandpaper::runtime::usb
