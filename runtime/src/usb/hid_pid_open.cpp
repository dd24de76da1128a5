// The HID PID driver's open sequence: the reports it reads and writes, in order, until each axis
// (two, or a wheel's one) holds a constant-force effect (docs/USB_PID.md, "Opening"); each failure names its step.
#include "sandpaper/runtime/usb/hid_pid_joystick.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <ctime>
#include <string>
#include <vector>

#include "hid_pid_internal.hpp"

namespace sandpaper::runtime::usb {
namespace {

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

}  // namespace

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
  axes_ = calibration_.wheel() ? 1 : 2;
  x_ = need(ReportType::Input, 0, kUsageX);
  if (axes_ == 2) {
    y_ = need(ReportType::Input, 0, kUsageY);
    if (x_.report_id != y_.report_id) fail_open(UsbStatus::Other, "X and Y are in different input reports");
  }
  magnitude_ = need(ReportType::Output, pid::kSetConstantForceReport, pid::kMagnitude);
  cf_block_ = need(ReportType::Output, pid::kSetConstantForceReport, pid::kEffectBlockIndex);
  need(ReportType::Output, pid::kSetEffectReport, pid::kEffectBlockIndex);
  need(ReportType::Output, pid::kSetEffectReport, pid::kEffectType);
  // One constant-force effect per axis, each enabled on its own axis: a device whose effects cannot
  // act on Y (the OpenFFBoard's 1-axis wheel descriptor) is played only as a wheel, with a device
  // file that says so.
  need(ReportType::Output, pid::kSetEffectReport, kUsageX);
  if (axes_ == 2 && !descriptor_.find(ReportType::Output, pid::kSetEffectReport, kUsageY))
    fail_open(UsbStatus::Other, "the HID report descriptor has no " + usage_name(kUsageY) + " in the report " +
                                    usage_name(pid::kSetEffectReport) + ": its effects act on one axis, and device file '" +
                                    calibration_.name + "' is for two; play it with a wheel's device file (one with a "
                                    "[wheel] table, such as openffboard-wheel)");
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
  fits(ReportType::Input, &x_, axes_ == 2 ? "position (X, Y)" : "position (X)");
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
    if (axis == &x_ || axes_ == 2)
      if (axis->logical_max <= axis->logical_min)
      fail_open(UsbStatus::Other, "the HID report descriptor's " + usage_name(axis->usage) + " (position) has the logical range " +
                                      std::to_string(axis->logical_min) + ".." + std::to_string(axis->logical_max) +
                                      ", which carries no position");

  // PID Pool: the device must hold one effect per axis at once.
  if (const HidField* max_effects = descriptor_.find(ReportType::Feature, pid::kPoolReport, pid::kSimultaneousEffectsMax)) {
    Buffer pool{};
    std::size_t length = 0;
    s = transport_.get_feature(max_effects->report_id, pool, length);
    if (s != UsbStatus::Ok) fail_step(s, "PID Pool", ReportType::Feature, max_effects->report_id, pid::kPoolReport);
    const auto simultaneous = read_field({pool.data(), length}, ids_, *max_effects);
    if (simultaneous < axes_)
      fail_open(UsbStatus::Other, "the device plays " + std::to_string(simultaneous) + " effect(s) at once; the driver needs " +
                                      std::to_string(axes_) + " (one constant force per axis)");
  }

  device_control(pid::kDcDeviceReset);
  device_control(pid::kDcEnableActuators);
  actuators_enabled_ = true;
  for (int axis = 0; axis < axes_; ++axis) create_effect(axis);

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
    for (std::uint32_t zero : {pid::kTriggerButton, pid::kTriggerRepeatInterval, pid::kSamplePeriod, pid::kStartDelay})
      if (const HidField* f = descriptor_.find(ReportType::Output, pid::kSetEffectReport, zero)) write_field(b, ids_, *f, 0);
    if (const HidField* f = descriptor_.find(ReportType::Output, pid::kSetEffectReport, kUsageX)) write_field(b, ids_, *f, axis == 0);
    if (const HidField* f = descriptor_.find(ReportType::Output, pid::kSetEffectReport, kUsageY)) write_field(b, ids_, *f, axis == 1);
    // Two axes: Direction Enable set and one polar direction, X's effect at 90 degrees and Y's at
    // 180, as Linux's hid-pidff sends every effect, so every HID PID joystick Linux plays reads it
    // alike: the OpenFFBoard gives X sin(angle) and Y -cos(angle) (HidFFB.cpp:320-321), +1 on each
    // effect's own axis and 0 on the other. Per-axis directions with Direction Enable clear are read
    // one way by the OpenFFBoard (linearly, HidFFB.cpp) and another by a device that takes them as
    // angles (the lab's SideWinder model), which then gives X nothing.
    // One axis (a wheel): Axes Enable X alone with Direction Enable clear, and the ordinal at its
    // logical maximum, which the OpenFFBoard's wheel reads as the factor +1; its 1-axis descriptor
    // puts Direction Enable where FFBWheel does not look for it (docs/DEVICES.md, "A wheel").
    const HidField* direction_enable = descriptor_.find(ReportType::Output, pid::kSetEffectReport, pid::kDirectionEnable);
    const bool polar = axes_ == 2 && direction_enable != nullptr && direction_enable->logical_max >= 1;
    if (direction_enable) write_field(b, ids_, *direction_enable, polar ? 1 : 0);
    // The ordinals also name Type Specific Block Offset fields: only those under Direction count.
    // Ordinal 1 spans a full turn over its logical range (as hid-pidff rescales 0..0xFFFF onto it).
    for (const HidField* f : descriptor_.find_all(ReportType::Output, pid::kSetEffectReport, usage(kOrdinalPage, 1)))
      if (f->parent_usage == pid::kDirection) {
        const double turn = static_cast<double>(f->logical_max - f->logical_min);
        const auto angle = [&](double degrees) { return f->logical_min + static_cast<std::int64_t>(std::lround(turn * degrees / 360)); };
        write_field(b, ids_, *f, polar ? angle(axis == 0 ? 90 : 180) : axis == 0 ? f->logical_max : 0);
      }
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

}  // namespace sandpaper::runtime::usb
