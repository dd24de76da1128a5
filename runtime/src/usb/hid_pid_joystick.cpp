// The HID PID driver's open, tick and shutdown sequences (docs/USB_PID.md lists them report by report).
#include "sandpaper/runtime/usb/hid_pid_joystick.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <ctime>
#include <string>
#include <vector>

namespace sandpaper::runtime::usb {
namespace {

// Reports read per tick at most: the device may interleave PID State reports with position
// reports, and a transport may have queued several (libusb_transport.hpp keeps 8).
constexpr int kReadsPerTick = 8;
// Reads while opening, each up to open_read_timeout_ms, before giving up on a position report.
constexpr int kOpenReads = 16;

std::string hex(std::uint32_t u) {
  static const char* digits = "0123456789ABCDEF";
  std::string s = "0x";
  for (int shift = 12; shift >= 0; shift -= 4) s += digits[(u >> shift) & 0xF];
  return s;
}

std::string hex_byte(std::uint8_t b) { return "0x" + hex(b).substr(4); }

std::string usage_name(std::uint32_t u) { return "page " + hex(u >> 16) + " usage " + hex(u & 0xFFFF); }

// The Device Control commands the open sequence sends, by name (for its errors).
std::string device_control_name(std::uint32_t command_usage) {
  if (command_usage == pid::kDcDeviceReset) return "Device Reset";
  if (command_usage == pid::kDcEnableActuators) return "Enable Actuators";
  return usage_name(command_usage);
}

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

std::int64_t monotonic_ns() noexcept {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return std::int64_t{now.tv_sec} * 1'000'000'000 + now.tv_nsec;
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
    : transport_(transport), calibration_(calibration), options_(options) {
  limits_.name = calibration.name;
  limits_.max_force_N = calibration.max_force_N;
  limits_.min_rate_hz = calibration.min_rate_hz;
  limits_.max_rate_hz = calibration.max_rate_hz;
  limits_.workspace_radius_m = calibration.workspace_radius_m;
  if (options_.stale_limit_s <= 0)
    options_.stale_limit_s = std::max(kDefaultStaleLimitS, 2 * calibration.usb_idle_report_period_s);
  open();
  position_raw_.store(pack_position(position_m_), std::memory_order_release);
  if (options_.io == HidPidIo::IoThread) start_io_thread();
}

HidPidJoystick::~HidPidJoystick() { close(); }

DeviceFault HidPidJoystick::last_fault_rt() const noexcept { return fault_.load(std::memory_order_acquire); }
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
      for (int axis = 0; axis < 2; ++axis) {
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

void HidPidJoystick::fail_open(UsbStatus status, const std::string& what) {
  close();
  throw HidPidError(status, what);
}

UsbStatus HidPidJoystick::write_open(std::span<const std::uint8_t> r) noexcept {
  const std::int64_t until = closed_ ? close_deadline_ns_
                                     : monotonic_ns() + std::int64_t{options_.open_write_timeout_ms} * 1'000'000;
  for (;;) {
    const UsbStatus s = transport_.write_output(r);
    if (s != UsbStatus::Timeout || monotonic_ns() >= until) return s;
  }
}

void HidPidJoystick::fail_step(UsbStatus status, const std::string& step, ReportType type, std::uint8_t report_id,
                               std::uint32_t report_usage) {
  const char* kind = type == ReportType::Feature ? "Feature" : type == ReportType::Output ? "Output" : "Input";
  std::string what = step + " failed: " + to_string(status) + " (" + kind + " report";
  if (ids_) what += " " + hex_byte(report_id);
  what += ", HID " + usage_name(report_usage) + ")";
  if (status == UsbStatus::Timeout && type != ReportType::Feature)
    what += " after " + std::to_string(options_.open_write_timeout_ms) + " ms of retries";
  fail_open(status, what);
}

void HidPidJoystick::open() {
  UsbStatus s = transport_.detach_kernel_driver();
  if (s != UsbStatus::Ok)
    fail_open(s, std::string("cannot detach the kernel's HID driver: ") + to_string(s));
  detached_ = true;
  s = transport_.claim_interface();
  if (s != UsbStatus::Ok) fail_open(s, std::string("cannot claim the HID interface: ") + to_string(s));
  claimed_ = true;

  std::vector<std::uint8_t> bytes;
  s = transport_.report_descriptor(bytes);
  if (s != UsbStatus::Ok) fail_open(s, std::string("cannot read the HID report descriptor: ") + to_string(s));
  try {
    descriptor_ = parse_hid_report_descriptor(bytes);
  } catch (const HidDescriptorError& e) {
    fail_open(UsbStatus::Other, e.what());
  }
  ids_ = descriptor_.uses_report_ids;

  const auto need = [&](ReportType type, std::uint32_t report_usage, std::uint32_t field_usage) -> const HidField& {
    const HidField* f = descriptor_.find(type, report_usage, field_usage);
    if (!f)
      fail_open(UsbStatus::Other, "the HID report descriptor has no " + usage_name(field_usage) +
                                      (report_usage ? " in the report " + usage_name(report_usage) : std::string()) +
                                      ": not a HID PID force-feedback joystick the driver can play");
    if (f->bit_size > 32)
      fail_open(UsbStatus::Other, "the HID report descriptor's " + usage_name(field_usage) + " is " +
                                      std::to_string(f->bit_size) + " bits wide; the driver reads and writes at most 32");
    return *f;
  };
  x_ = need(ReportType::Input, 0, kUsageX);
  y_ = need(ReportType::Input, 0, kUsageY);
  if (x_.report_id != y_.report_id) fail_open(UsbStatus::Other, "X and Y are in different input reports");
  magnitude_ = need(ReportType::Output, pid::kSetConstantForceReport, pid::kMagnitude);
  cf_block_ = need(ReportType::Output, pid::kSetConstantForceReport, pid::kEffectBlockIndex);
  need(ReportType::Output, pid::kSetEffectReport, pid::kEffectBlockIndex);
  need(ReportType::Output, pid::kSetEffectReport, pid::kEffectType);
  // One constant-force effect per axis, each enabled on its own axis: a device whose effects cannot
  // act on Y (the OpenFFBoard's 1-axis wheel descriptor) is not a 2-axis joystick.
  need(ReportType::Output, pid::kSetEffectReport, kUsageX);
  need(ReportType::Output, pid::kSetEffectReport, kUsageY);
  need(ReportType::Output, pid::kEffectOperationReport, pid::kEffectBlockIndex);
  need(ReportType::Output, pid::kEffectOperationReport, pid::kEffectOperation);
  if (!device_control_field(pid::kDcEnableActuators) || !device_control_field(pid::kDcDeviceReset))
    fail_open(UsbStatus::Other, "the HID report descriptor has no Device Control report with Enable Actuators and Device Reset "
                                "(an array in report " + usage_name(pid::kDeviceControlReport) + ", or bits in report " +
                                usage_name(pid::kDeviceControlBitsReport) + "): not a HID PID force-feedback joystick the driver can play");
  need(ReportType::Feature, pid::kCreateNewEffectReport, pid::kEffectType);
  need(ReportType::Feature, pid::kBlockLoadReport, pid::kEffectBlockIndex);
  need(ReportType::Feature, pid::kBlockLoadReport, pid::kBlockLoadStatus);
  // Every report the driver builds or reads is one 64-byte buffer: a descriptor that makes one
  // longer is refused here, or the transfer would read past the buffer (docs/RELIABILITY.md, F23).
  const auto fits = [&](ReportType type, const HidField* f, const char* name) {
    if (!f) return;
    const std::size_t length = descriptor_.report_bytes(type, f->report_id);
    if (length > kMaxReport)
      fail_open(UsbStatus::Other, std::string("the HID report descriptor's ") + name + " report (ID " +
                                      std::to_string(f->report_id) + ") is " + std::to_string(length) +
                                      " bytes; the driver sends and reads reports of at most " +
                                      std::to_string(kMaxReport) + " (a full-speed interrupt packet)");
  };
  fits(ReportType::Input, &x_, "position (X, Y)");
  fits(ReportType::Output, &magnitude_, "Set Constant Force");
  fits(ReportType::Output, descriptor_.find(ReportType::Output, pid::kSetEffectReport, pid::kEffectBlockIndex), "Set Effect");
  fits(ReportType::Output, descriptor_.find(ReportType::Output, pid::kEffectOperationReport, pid::kEffectBlockIndex),
       "Effect Operation");
  fits(ReportType::Output, descriptor_.find(ReportType::Output, pid::kBlockFreeReport, pid::kEffectBlockIndex), "Block Free");
  for (std::uint32_t command : {pid::kDcEnableActuators, pid::kDcDisableActuators, pid::kDcStopAllEffects, pid::kDcDeviceReset})
    fits(ReportType::Output, device_control_field(command), "Device Control");
  fits(ReportType::Feature, descriptor_.find(ReportType::Feature, pid::kCreateNewEffectReport, pid::kEffectType),
       "Create New Effect");
  fits(ReportType::Feature, descriptor_.find(ReportType::Feature, pid::kBlockLoadReport, pid::kEffectBlockIndex), "Block Load");
  fits(ReportType::Feature, descriptor_.find(ReportType::Feature, pid::kPoolReport, pid::kSimultaneousEffectsMax), "PID Pool");
  cf_bytes_ = descriptor_.report_bytes(ReportType::Output, magnitude_.report_id);
  // Zero force must be sendable, and each sense of it (F24): a Magnitude range that misses zero
  // would turn a commanded zero into a push, and made the tick's clamp bounds cross.
  if (!(magnitude_.logical_min < 0 && magnitude_.logical_max > 0))
    fail_open(UsbStatus::Other, "the HID report descriptor's Magnitude (Set Constant Force) has the logical range " +
                                    std::to_string(magnitude_.logical_min) + ".." + std::to_string(magnitude_.logical_max) +
                                    "; the driver needs one with negative and positive values (zero force inside it)");
  for (const HidField* axis : {&x_, &y_})
    if (axis->logical_max <= axis->logical_min)
      fail_open(UsbStatus::Other, "the HID report descriptor's " + usage_name(axis->usage) + " (position) has the logical range " +
                                      std::to_string(axis->logical_min) + ".." + std::to_string(axis->logical_max) +
                                      ", which carries no position");

  // PID Pool: the device must hold two effects at once.
  if (const HidField* max_effects = descriptor_.find(ReportType::Feature, pid::kPoolReport, pid::kSimultaneousEffectsMax)) {
    Buffer pool{};
    std::size_t length = 0;
    s = transport_.get_feature(max_effects->report_id, pool, length);
    if (s != UsbStatus::Ok) fail_step(s, "PID Pool", ReportType::Feature, max_effects->report_id, pid::kPoolReport);
    const auto simultaneous = read_field({pool.data(), length}, ids_, *max_effects);
    if (simultaneous < 2)
      fail_open(UsbStatus::Other, "the device plays " + std::to_string(simultaneous) +
                                      " effect(s) at once; the driver needs 2 (one constant force per axis)");
  }

  device_control(pid::kDcDeviceReset);
  device_control(pid::kDcEnableActuators);
  actuators_enabled_ = true;
  create_effect(0);
  create_effect(1);

  // The first position report may have waited in the device since before the claim (a kernel
  // driver that nobody had opened does not poll): the second one is where the handle is now.
  int positions = 0;
  for (int attempt = 0; attempt < kOpenReads; ++attempt) {
    std::size_t length = 0;
    s = transport_.read_input(input_, length, options_.open_read_timeout_ms);
    if (s == UsbStatus::Ok && decode_position({input_.data(), length}, position_m_) && ++positions == 2) {
      for (int more = 0; more < kReadsPerTick; ++more) {  // and any queued behind it
        if (transport_.read_input(input_, length, 0) != UsbStatus::Ok) break;
        decode_position({input_.data(), length}, position_m_);
      }
      return;
    }
    // A device that reports only on change, and has not moved since: the one report is current.
    if (s == UsbStatus::Timeout && positions == 1) return;
    if (s != UsbStatus::Ok && s != UsbStatus::Timeout)
      fail_open(s, std::string("cannot read the position: ") + to_string(s));
  }
  fail_open(UsbStatus::Timeout, "the device sent no position report while opening");
}

const HidField* HidPidJoystick::device_control_field(std::uint32_t command_usage) const {
  // The array form: one field whose value selects the command.
  if (const HidField* f = descriptor_.find(ReportType::Output, pid::kDeviceControlReport, pid::kDeviceControlReport))
    return f->array_value(command_usage) ? f : nullptr;
  // The bitmask form: a 1-bit variable per command, in report 0x95 (or, as some descriptors put it, 0x96).
  for (std::uint32_t report_usage : {pid::kDeviceControlBitsReport, pid::kDeviceControlReport})
    if (const HidField* f = descriptor_.find(ReportType::Output, report_usage, command_usage); f && f->variable) return f;
  return nullptr;
}

void HidPidJoystick::device_control(std::uint32_t command_usage) {
  const HidField* field = device_control_field(command_usage);
  if (!field) return;  // optional commands of the shutdown (open() checked the ones it needs)
  const HidField& f = *field;
  Buffer b{};
  b[0] = f.report_id;
  // Array: the command's value. Bits: this command's bit set, every other clear (the OpenFFBoard
  // acts on each set bit in turn, HidFFB.cpp:205-224).
  write_field(b, ids_, f, f.variable ? 1 : *f.array_value(command_usage));
  const UsbStatus s = write_open(report(b, descriptor_.report_bytes(ReportType::Output, f.report_id)));
  if (closed_) return;  // the shutdown sequence: best effort
  if (s != UsbStatus::Ok)
    fail_step(s, "Device Control (" + device_control_name(command_usage) + ")", ReportType::Output, f.report_id, f.report_usage);
}

void HidPidJoystick::create_effect(int axis) {
  const auto a = static_cast<std::size_t>(axis);
  // Create New Effect (feature): type Constant Force, Byte Count 0 (no custom data).
  {
    const HidField& type = *descriptor_.find(ReportType::Feature, pid::kCreateNewEffectReport, pid::kEffectType);
    const auto constant = type.array_value(pid::kEtConstantForce);
    if (!constant) fail_open(UsbStatus::Other, "the device does not offer constant-force effects");
    Buffer b{};
    b[0] = type.report_id;
    write_field(b, ids_, type, *constant);
    const UsbStatus s = transport_.set_feature(report(b, descriptor_.report_bytes(ReportType::Feature, type.report_id)));
    if (s != UsbStatus::Ok) fail_step(s, "Create New Effect", ReportType::Feature, type.report_id, pid::kCreateNewEffectReport);
  }
  // Block Load (feature, read back): the effect block index the device gave the new effect.
  {
    const HidField& index = *descriptor_.find(ReportType::Feature, pid::kBlockLoadReport, pid::kEffectBlockIndex);
    const HidField& status = *descriptor_.find(ReportType::Feature, pid::kBlockLoadReport, pid::kBlockLoadStatus);
    Buffer b{};
    std::size_t length = 0;
    const UsbStatus s = transport_.get_feature(index.report_id, b, length);
    if (s != UsbStatus::Ok) fail_step(s, "Block Load", ReportType::Feature, index.report_id, pid::kBlockLoadReport);
    const std::span<const std::uint8_t> got{b.data(), length};
    const std::uint32_t load = status.array_usage(static_cast<std::int32_t>(read_field(got, ids_, status)));
    if (load != pid::kBlockLoadSuccess)
      fail_open(UsbStatus::Other, load == pid::kBlockLoadFull ? "the device's effect memory is full (Block Load: full)"
                                                              : "the device refused the effect (Block Load: error)");
    const auto block = read_field(got, ids_, index);
    if (block < 1 || block > 255) fail_open(UsbStatus::Other, "Block Load gave effect block index " + std::to_string(block));
    block_index_[a] = static_cast<std::uint8_t>(block);
  }
  // Set Effect: constant force, infinite duration, full gain, no trigger, on this axis only.
  {
    const HidField& index = *descriptor_.find(ReportType::Output, pid::kSetEffectReport, pid::kEffectBlockIndex);
    Buffer b{};
    b[0] = index.report_id;
    write_field(b, ids_, index, block_index_[a]);
    const HidField& type = *descriptor_.find(ReportType::Output, pid::kSetEffectReport, pid::kEffectType);
    const auto constant = type.array_value(pid::kEtConstantForce);
    if (!constant) fail_open(UsbStatus::Other, "Set Effect does not offer constant-force effects");
    write_field(b, ids_, type, *constant);
    // Infinite duration: the null value, all bits set (0xFFFF for 16 bits), as HID PID 1.0 allows
    // for Duration and as Linux's hid-pidff sends.
    if (const HidField* f = descriptor_.find(ReportType::Output, pid::kSetEffectReport, pid::kDuration))
      write_field(b, ids_, *f, -1);
    if (const HidField* f = descriptor_.find(ReportType::Output, pid::kSetEffectReport, pid::kGain))
      write_field(b, ids_, *f, f->logical_max);
    // Trigger Button 0 lies outside its logical range 1..n: the null value, no trigger.
    for (std::uint32_t zero : {pid::kTriggerButton, pid::kTriggerRepeatInterval, pid::kSamplePeriod, pid::kStartDelay,
                               pid::kDirectionEnable})
      if (const HidField* f = descriptor_.find(ReportType::Output, pid::kSetEffectReport, zero)) write_field(b, ids_, *f, 0);
    if (const HidField* f = descriptor_.find(ReportType::Output, pid::kSetEffectReport, kUsageX)) write_field(b, ids_, *f, axis == 0);
    if (const HidField* f = descriptor_.find(ReportType::Output, pid::kSetEffectReport, kUsageY)) write_field(b, ids_, *f, axis == 1);
    // Direction Enable clear: Axes Enable picks the axis, and the OpenFFBoard scales the enabled axis
    // linearly by its direction ordinal, X by (dir - 18000) / 18000 and Y by -(dir - 18000) / 18000
    // (HidFFB.cpp:316-317, directions 0..36000). The X effect's ordinal 1 at its logical maximum
    // (360 degrees) and the Y effect's ordinal 2 at 0 give both axes the factor +1, so a positive
    // magnitude means the same sense on both. (All ordinals 0, as before, gave X -1 and Y +1.) For
    // a device that reads the ordinals as an angle, 360 and 0 degrees are the same direction.
    // The ordinals also name Type Specific Block Offset fields: only those under Direction count.
    for (const HidField* f : descriptor_.find_all(ReportType::Output, pid::kSetEffectReport, usage(kOrdinalPage, 1)))
      if (f->parent_usage == pid::kDirection) write_field(b, ids_, *f, axis == 0 ? f->logical_max : 0);
    const UsbStatus s = write_open(report(b, descriptor_.report_bytes(ReportType::Output, index.report_id)));
    if (s != UsbStatus::Ok) fail_step(s, "Set Effect", ReportType::Output, index.report_id, pid::kSetEffectReport);
  }
  // Set Constant Force 0, preformatted once: the tick only rewrites the magnitude.
  cf_report_[a].fill(0);
  cf_report_[a][0] = magnitude_.report_id;
  write_field(cf_report_[a], ids_, cf_block_, block_index_[a]);
  write_field(cf_report_[a], ids_, magnitude_, 0);
  if (const UsbStatus s = write_open({cf_report_[a].data(), cf_bytes_}); s != UsbStatus::Ok)
    fail_step(s, "Set Constant Force", ReportType::Output, magnitude_.report_id, pid::kSetConstantForceReport);
  last_command_[a].store(0, std::memory_order_relaxed);
  // Effect Operation: start, loop count 1.
  {
    const HidField& index = *descriptor_.find(ReportType::Output, pid::kEffectOperationReport, pid::kEffectBlockIndex);
    const HidField& op = *descriptor_.find(ReportType::Output, pid::kEffectOperationReport, pid::kEffectOperation);
    const auto start = op.array_value(pid::kOpEffectStart);
    if (!start) fail_open(UsbStatus::Other, "the Effect Operation report lacks Op Effect Start");
    Buffer b{};
    b[0] = index.report_id;
    write_field(b, ids_, index, block_index_[a]);
    write_field(b, ids_, op, *start);
    if (const HidField* f = descriptor_.find(ReportType::Output, pid::kEffectOperationReport, pid::kLoopCount))
      write_field(b, ids_, *f, 1);
    const UsbStatus s = write_open(report(b, descriptor_.report_bytes(ReportType::Output, index.report_id)));
    if (s != UsbStatus::Ok) fail_step(s, "Effect Operation (start)", ReportType::Output, index.report_id, pid::kEffectOperationReport);
    started_[a] = true;
  }
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
  return send_constant_force(1, y) && ok;
}

bool HidPidJoystick::decode_position(std::span<const std::uint8_t> report, glm::dvec2& position_m) const noexcept {
  if (ids_ && (report.empty() || report[0] != x_.report_id)) return false;
  const std::size_t need = descriptor_.report_bytes(ReportType::Input, x_.report_id);
  if (report.size() < need) return false;
  const HidField* axes[2] = {&x_, &y_};
  for (int a = 0; a < 2; ++a) {
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
