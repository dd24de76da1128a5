// The HID PID 1.0 device model: the reports of pid1_01 (usage page 0x0F) read and answered as the
// class definition describes them, over the HID 1.11 control requests (section 7.2) and interrupt
// endpoints.
#include "hid_pid_device.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace sandpaper::usb_lab {
namespace {

using hid::ReportField;
using hid::ReportType;
using hid::usage;

// Usages of the PID page (0x0F), pid1_01 section 5 (usage table), and of the Generic Desktop (0x01)
// and Ordinal (0x0A) pages (HID Usage Tables 1.12).
constexpr std::uint16_t kPid = 0x0F;
constexpr std::uint32_t kX = usage(0x01, 0x30), kY = usage(0x01, 0x31);
constexpr std::uint32_t kOrdinal1 = usage(0x0A, 0x01);
constexpr std::uint32_t kSetEffectReport = usage(kPid, 0x21), kEffectBlockIndex = usage(kPid, 0x22),
                        kEffectType = usage(kPid, 0x25), kEtConstantForce = usage(kPid, 0x26),
                        kDuration = usage(kPid, 0x50), kGain = usage(kPid, 0x52), kAxesEnable = usage(kPid, 0x55),
                        kDirectionEnable = usage(kPid, 0x56), kDirection = usage(kPid, 0x57),
                        kMagnitude = usage(kPid, 0x70), kSetConstantForceReport = usage(kPid, 0x73),
                        kEffectOperationReport = usage(kPid, 0x77), kEffectOperation = usage(kPid, 0x78),
                        kOpEffectStart = usage(kPid, 0x79), kOpEffectStartSolo = usage(kPid, 0x7A),
                        kOpEffectStop = usage(kPid, 0x7B), kLoopCount = usage(kPid, 0x7C),
                        kDeviceGainReport = usage(kPid, 0x7D), kDeviceGain = usage(kPid, 0x7E),
                        kPoolReport = usage(kPid, 0x7F), kRamPoolSize = usage(kPid, 0x80),
                        kSimultaneousEffectsMax = usage(kPid, 0x83), kBlockLoadReport = usage(kPid, 0x89),
                        kBlockLoadStatus = usage(kPid, 0x8B), kBlockLoadSuccess = usage(kPid, 0x8C),
                        kBlockLoadFull = usage(kPid, 0x8D), kBlockLoadError = usage(kPid, 0x8E),
                        kBlockFreeReport = usage(kPid, 0x90), kPidStateReport = usage(kPid, 0x92),
                        kEffectPlaying = usage(kPid, 0x94), kDeviceControlReport = usage(kPid, 0x95),
                        kDeviceControl = usage(kPid, 0x96), kDcEnableActuators = usage(kPid, 0x97),
                        kDcDisableActuators = usage(kPid, 0x98), kDcStopAllEffects = usage(kPid, 0x99),
                        kDcDeviceReset = usage(kPid, 0x9A), kDcDevicePause = usage(kPid, 0x9B),
                        kDcDeviceContinue = usage(kPid, 0x9C), kDevicePaused = usage(kPid, 0x9F),
                        kActuatorsEnabled = usage(kPid, 0xA0), kSafetySwitch = usage(kPid, 0xA4),
                        kActuatorOverrideSwitch = usage(kPid, 0xA5), kActuatorPower = usage(kPid, 0xA6),
                        kStartDelay = usage(kPid, 0xA7), kDeviceManagedPool = usage(kPid, 0xA9),
                        kSharedParameterBlocks = usage(kPid, 0xAA), kCreateNewEffectReport = usage(kPid, 0xAB),
                        kRamPoolAvailable = usage(kPid, 0xAC);
// The type-specific parameter reports (pid1_01 Set Envelope, Set Condition, Set Periodic, Set
// Constant Force, Set Ramp Force, Set Custom Force): what one effect block holds besides Set Effect.
constexpr std::uint32_t kParameterReports[] = {usage(kPid, 0x5A), usage(kPid, 0x5F), usage(kPid, 0x6E),
                                               kSetConstantForceReport, usage(kPid, 0x74), usage(kPid, 0x6B)};

// USB 2.0 section 9.4 and HID 1.11 section 7.2 request codes.
constexpr std::uint8_t kGetDescriptor = 0x06;
constexpr std::uint8_t kGetReport = 0x01, kGetIdle = 0x02, kSetReport = 0x09, kSetIdle = 0x0A;
constexpr std::uint8_t kHidDescriptorType = 0x21, kReportDescriptorType = 0x22;

constexpr double kFullScale = 32767.0;  // TorqueUpdate's int16 full scale

std::int16_t to_torque(double fraction) {
  return static_cast<std::int16_t>(std::lround(std::clamp(fraction, -1.0, 1.0) * kFullScale));
}

bool is_class_interface(const SetupPacket& s) { return (s.bmRequestType & 0x7F) == 0x21; }
bool is_standard_interface(const SetupPacket& s) { return (s.bmRequestType & 0x7F) == 0x01; }

}  // namespace

HidPidDevice::HidPidDevice(DeviceIdentity identity, std::vector<std::uint8_t> report_descriptor,
                           InterruptEndpoints endpoints, std::uint16_t bcd_hid)
    : identity_(std::move(identity)),
      descriptor_bytes_(std::move(report_descriptor)),
      descriptor_(hid::parse_report_descriptor(descriptor_bytes_)),
      endpoints_(endpoints),
      bcd_hid_(bcd_hid) {
  const auto need = [](const Report& r, const char* name) {
    if (!r.present) throw std::runtime_error(std::string("HidPidDevice: the report descriptor has no ") + name + " report");
  };
  set_effect_ = find_report(ReportType::Output, kSetEffectReport);
  set_cf_ = find_report(ReportType::Output, kSetConstantForceReport);
  effect_op_ = find_report(ReportType::Output, kEffectOperationReport);
  block_free_ = find_report(ReportType::Output, kBlockFreeReport);
  device_control_ = find_report(ReportType::Output, kDeviceControlReport);
  if (!device_control_.present) device_control_ = find_report(ReportType::Output, kDeviceControl);
  gain_report_ = find_report(ReportType::Output, kDeviceGainReport);
  create_effect_ = find_report(ReportType::Feature, kCreateNewEffectReport);
  block_load_ = find_report(ReportType::Feature, kBlockLoadReport);
  pool_ = find_report(ReportType::Feature, kPoolReport);
  pid_state_ = find_report(ReportType::Input, kPidStateReport);
  need(set_effect_, "Set Effect");
  need(set_cf_, "Set Constant Force");
  need(effect_op_, "Effect Operation");
  need(create_effect_, "Create New Effect");
  need(block_load_, "Block Load");

  // The position report: the input report that carries X and Y outside the PID collections.
  for (const ReportField& f : descriptor_.fields)
    if (f.type == ReportType::Input && f.variable && !f.constant)
      for (std::size_t i = 0; i < f.count; ++i)
        if (f.element_usage(i) == kX && !x_) {
          x_ = Field{&f, i};
          input_.id = f.report_id;
        }
  if (x_) y_ = find(ReportType::Input, input_.id, kY);
  if (!x_ || !y_) throw std::runtime_error("HidPidDevice: the report descriptor has no input report with X and Y");
  input_.present = true;
  input_.bytes = descriptor_.report_bytes(ReportType::Input, input_.id);

  if (const Field m = find(ReportType::Output, set_cf_.id, kMagnitude)) magnitude_max_ = m.field->logical_max;
  if (const Field g = find(ReportType::Output, set_effect_.id, kGain)) gain_max_ = g.field->logical_max;
  if (gain_report_.present)
    if (const Field g = find(ReportType::Output, gain_report_.id, kDeviceGain)) device_gain_max_ = g.field->logical_max;
  if (magnitude_max_ <= 0 || gain_max_ <= 0 || device_gain_max_ <= 0)
    throw std::runtime_error("HidPidDevice: Magnitude, Gain or Device Gain has no positive logical maximum");

  // As many effect blocks as Block Load's Effect Block Index can name (1..40 on the FF2): the pool
  // the model manages itself (Device Managed Pool, pid_pool()).
  const Field index = find(ReportType::Feature, block_load_.id, kEffectBlockIndex);
  if (!index) throw std::runtime_error("HidPidDevice: Block Load has no Effect Block Index");
  const std::int64_t blocks = std::int64_t{index.field->logical_max} - std::max(index.field->logical_min, 1) + 1;
  if (index.field->logical_min > 1 || blocks < 1)
    throw std::runtime_error("HidPidDevice: Block Load's Effect Block Index range does not start at 1");
  blocks_.resize(static_cast<std::size_t>(std::min<std::int64_t>(blocks, 255)));
  last_input_sent_ = Clock::now();
}

HidPidDevice::Report HidPidDevice::find_report(ReportType type, std::uint32_t report_usage) const {
  for (const ReportField& f : descriptor_.fields)
    if (f.type == type && std::find(f.collections.begin(), f.collections.end(), report_usage) != f.collections.end())
      return Report{f.report_id, descriptor_.report_bytes(type, f.report_id), true};
  return {};
}

// A field by usage in report (type, id): a Variable element with that usage, or an Array named by
// it (its innermost collection, as Effect Type, Effect Operation and Block Load Status are named
// arrays, or its only usage). `parent`: only fields whose innermost collection is that usage.
HidPidDevice::Field HidPidDevice::find(ReportType type, std::uint8_t id, std::uint32_t u, std::uint32_t parent) const {
  for (const ReportField& f : descriptor_.fields) {
    if (f.type != type || f.report_id != id || f.constant) continue;
    if (parent != 0 && f.innermost_collection() != parent) continue;
    if (f.variable) {
      for (std::size_t i = 0; i < f.count; ++i)
        if (f.element_usage(i) == u) return Field{&f, i};
    } else if (f.innermost_collection() == u || (f.usages.size() == 1 && f.usages.front() == u)) {
      return Field{&f, 0};
    }
  }
  return {};
}

std::span<const std::uint8_t> HidPidDevice::payload(std::span<const std::uint8_t> report) const {
  return descriptor_.uses_report_ids && !report.empty() ? report.subspan(1) : report;
}

std::int64_t HidPidDevice::get(std::span<const std::uint8_t> data, Field f) const {
  return f ? hid::read_field(data, *f.field, f.element) : 0;
}

void HidPidDevice::put(std::span<std::uint8_t> data, Field f, std::int64_t value) const {
  if (f) hid::write_field(descriptor_.uses_report_ids ? data.subspan(1) : data, *f.field, value, f.element);
}

// ---- descriptors and the control pipe ----

std::vector<std::uint8_t> HidPidDevice::function_descriptors() const {
  const auto lo = [](std::size_t v) { return static_cast<std::uint8_t>(v & 0xFF); };
  const auto hi = [](std::size_t v) { return static_cast<std::uint8_t>((v >> 8) & 0xFF); };
  return {
      // Interface 0: HID (0x03), no boot subclass, two endpoints (USB 2.0 section 9.6.5).
      9, 0x04, 0, 0, 2, 0x03, 0, 0, 0,
      // HID descriptor (HID 1.11 section 6.2.1): one report descriptor.
      9, kHidDescriptorType, lo(bcd_hid_), hi(bcd_hid_), 0, 1, kReportDescriptorType, lo(descriptor_bytes_.size()),
      hi(descriptor_bytes_.size()),
      // Interrupt IN 0x81 and OUT 0x02 (USB 2.0 section 9.6.6).
      7, 0x05, 0x81, 0x03, lo(endpoints_.in_max_packet), hi(endpoints_.in_max_packet), endpoints_.in_interval,
      7, 0x05, 0x02, 0x03, lo(endpoints_.out_max_packet), hi(endpoints_.out_max_packet), endpoints_.out_interval};
}

void HidPidDevice::configured() {
  std::lock_guard lock(mutex_);
  configured_ = true;
  pending_in_.clear();
  queue_input(joystick_report());  // the host has seen no state yet: the first report is a change
}

void HidPidDevice::deconfigured() {
  std::lock_guard lock(mutex_);
  configured_ = false;
  pending_in_.clear();
}

void HidPidDevice::suspended(bool) {}

bool HidPidDevice::accepts(const SetupPacket& s) const {
  if (is_standard_interface(s)) return s.bRequest == kGetDescriptor && s.device_to_host();
  if (!is_class_interface(s)) return false;
  const auto type = static_cast<ReportType>(s.wValue >> 8);
  const auto id = static_cast<std::uint8_t>(s.wValue & 0xFF);
  switch (s.bRequest) {
    case kGetReport: return s.device_to_host();
    case kGetIdle: return s.device_to_host();
    case kSetIdle: return !s.device_to_host();
    case kSetReport:
      if (s.device_to_host()) return false;
      if (type == ReportType::Feature) return id == create_effect_.id;
      return type == ReportType::Output && descriptor_.report_bytes(ReportType::Output, id) > 0;
    default: return false;  // GET/SET_PROTOCOL: for boot devices only (HID 1.11 sections 7.2.5, 7.2.6)
  }
}

ControlReply HidPidDevice::control(const SetupPacket& s, std::span<const std::uint8_t> out_data) {
  const ControlReply stall{true, {}};
  if (!accepts(s)) return stall;
  if (is_standard_interface(s)) {  // GET_DESCRIPTOR of the interface's class descriptors (HID 1.11 section 7.1.1)
    if ((s.wValue >> 8) == kReportDescriptorType) return ControlReply{false, descriptor_bytes_};
    if ((s.wValue >> 8) == kHidDescriptorType) {
      const std::vector<std::uint8_t> all = function_descriptors();
      return ControlReply{false, {all.begin() + 9, all.begin() + 18}};
    }
    return stall;
  }
  const auto type = static_cast<ReportType>(s.wValue >> 8);
  const auto id = static_cast<std::uint8_t>(s.wValue & 0xFF);
  std::unique_lock lock(mutex_);
  const auto now = Clock::now();
  ControlReply reply;
  switch (s.bRequest) {
    case kSetIdle:  // HID 1.11 section 7.2.4: wValue high byte the duration in 4 ms units, 0 infinite
      idle_4ms_ = static_cast<std::uint8_t>(s.wValue >> 8);
      input_ready_.notify_all();
      return reply;
    case kGetIdle:
      return ControlReply{false, {idle_4ms_}};
    case kGetReport:  // HID 1.11 section 7.2.1
      if (type == ReportType::Input && id == input_.id) reply.data = joystick_report();
      else if (type == ReportType::Input && pid_state_.present && id == pid_state_.id) reply.data = pid_state_report(0);
      else if (type == ReportType::Feature && id == block_load_.id) reply.data = block_load();
      else if (type == ReportType::Feature && pool_.present && id == pool_.id) reply.data = pid_pool();
      else return stall;
      return reply;
    case kSetReport:  // HID 1.11 section 7.2.2: the data stage is the report, ID byte first when IDs are used
      if (descriptor_.uses_report_ids && (out_data.empty() || out_data[0] != id)) {
        ++rejected_;
        return reply;  // past the data stage: too late to stall
      }
      if (type == ReportType::Feature) create_new_effect(payload(out_data));
      else handle_output(out_data);
      break;
    default: return stall;
  }
  refresh_and_notify(lock, now);
  return reply;
}

// ---- the interrupt endpoints ----

void HidPidDevice::interrupt_out(std::span<const std::uint8_t> data) {
  std::unique_lock lock(mutex_);
  handle_output(data);
  refresh_and_notify(lock, Clock::now());
}

bool HidPidDevice::next_interrupt_in(std::vector<std::uint8_t>& report, std::chrono::microseconds wait) {
  std::unique_lock lock(mutex_);
  const auto deadline = Clock::now() + wait;
  for (;;) {
    const auto now = Clock::now();
    if (!pending_in_.empty()) {
      report = std::move(pending_in_.begin()->second);
      pending_in_.erase(pending_in_.begin());
      in_flight_ = report;
      last_input_sent_ = now;
      return true;
    }
    const auto idle = std::chrono::milliseconds(4 * idle_4ms_);
    if (idle_4ms_ != 0 && now >= last_input_sent_ + idle) {
      report = joystick_report();
      in_flight_ = report;
      last_input_sent_ = now;
      return true;
    }
    if (now >= deadline) return false;
    input_ready_.wait_until(lock, idle_4ms_ != 0 ? std::min(deadline, last_input_sent_ + idle) : deadline);
  }
}

void HidPidDevice::interrupt_in_done(bool delivered) {
  std::lock_guard lock(mutex_);
  // A report the host never took is still the news it was, unless a newer one replaced it.
  if (!delivered && !in_flight_.empty()) {
    const std::uint8_t id = descriptor_.uses_report_ids ? in_flight_.front() : 0;
    pending_in_.try_emplace(id, std::move(in_flight_));
    input_ready_.notify_all();
  }
  in_flight_.clear();
}

void HidPidDevice::queue_input(std::vector<std::uint8_t> report) {
  if (report.empty()) return;
  const std::uint8_t id = descriptor_.uses_report_ids ? report.front() : 0;
  pending_in_[id] = std::move(report);
  input_ready_.notify_all();
}

// ---- the hand and the forces ----

void HidPidDevice::set_position(int axis, double fraction_of_range) {
  if (axis < 0 || axis > 1) throw std::out_of_range("HidPidDevice: axis " + std::to_string(axis) + " (0 X, 1 Y)");
  std::unique_lock lock(mutex_);
  const std::vector<std::uint8_t> before = joystick_report();
  position_[static_cast<std::size_t>(axis)] = std::clamp(fraction_of_range, -1.0, 1.0);
  std::vector<std::uint8_t> after = joystick_report();
  if (after != before && configured_) queue_input(std::move(after));
  refresh_and_notify(lock, Clock::now());
}

// The torque changes queued under the lock go to the observer after it is released, in order
// across threads (observer_mutex_ is taken before the device's lock is let go).
void HidPidDevice::refresh_and_notify(std::unique_lock<std::mutex>& lock, Clock::time_point now) {
  refresh(now);
  std::vector<TorqueUpdate> updates;
  updates.swap(updates_);
  std::lock_guard order(observer_mutex_);
  lock.unlock();
  for (const TorqueUpdate& u : updates)
    if (observer_) observer_(u);
}

void HidPidDevice::on_torque(std::function<void(const TorqueUpdate&)> observer) {
  std::lock_guard order(observer_mutex_);
  observer_ = std::move(observer);
}

void HidPidDevice::update() {
  std::unique_lock lock(mutex_);
  refresh_and_notify(lock, Clock::now());
}

std::array<double, 2> HidPidDevice::force() const {
  std::lock_guard lock(mutex_);
  return force_locked();
}

HidPidDeviceState HidPidDevice::state() const {
  std::lock_guard lock(mutex_);
  HidPidDeviceState s;
  s.actuators_enabled = actuators_enabled_;
  s.paused = paused_;
  s.effects_in_use = blocks_in_use();
  for (const Effect& e : blocks_) s.effects_playing += e.allocated && e.playing;
  s.device_gain = device_gain_;
  for (std::size_t a = 0; a < 2; ++a) {
    s.torque[a] = torque_[a];
    s.torque_updates[a] = torque_updates_[a];
  }
  s.reports_rejected = rejected_;
  return s;
}

// The direction an effect pushes the handle, as a unit vector (X, Y) in the input report's axes
// (X right, Y toward the user).
//
// Direction Enable set: the effect has one direction, polar, in Direction's Ordinal 1 (an angle:
// the FF2 declares it 0..255 logical over 0..36000 physical at Unit Exponent -2, degrees), and
// Axes Enable is ignored (pid1_01, Set Effect Report: Direction Enable, Direction). The angle is
// read as DirectInput's polar direction, the model PID 1.0 encodes and the FF2 (Microsoft's own
// PID device, its Direction in DirectInput's hundredths of a degree) was made for ("Effect
// Direction", DirectX 9 SDK): 0 degrees is north, the -Y end (away from the user), angles grow
// clockwise (90 degrees east, +X), and the direction is the one the force comes FROM, so a
// positive magnitude pushes the handle toward the opposite side. 0 degrees pushes toward +Y, 90
// degrees toward -X. Linux agrees (include/uapi/linux/input.h: direction 0 "down", 0x4000
// "left", the sense the force acts in; hid-pidff sends it to Direction unchanged).
//
// Direction Enable clear: Axes Enable picks the axes the effect acts on; the model keeps the same
// polar direction and drops its components on axes not enabled. (An effect on X alone whose
// direction points north therefore has no force at all.)
static std::array<double, 2> direction_vector(bool direction_enabled, const bool axes_enabled[2], double degrees) {
  const double rad = degrees * std::numbers::pi / 180.0;
  std::array<double, 2> v{-std::sin(rad), std::cos(rad)};
  if (!direction_enabled)
    for (std::size_t a = 0; a < 2; ++a)
      if (!axes_enabled[a]) v[a] = 0;
  return v;
}

std::array<double, 2> HidPidDevice::force_locked() const {
  std::array<double, 2> f{0, 0};
  if (!actuators_enabled_ || paused_) return f;
  const auto now = Clock::now();
  for (const Effect& e : blocks_) {
    if (!e.allocated || !e.playing || e.type != kEtConstantForce) continue;
    if (now < e.started + std::chrono::duration<double>(e.start_delay_s)) continue;
    const double amount = e.magnitude * e.gain * device_gain_;
    const std::array<double, 2> d = direction_vector(e.direction_enabled, e.axes_enabled, e.direction_deg);
    for (std::size_t a = 0; a < 2; ++a) f[a] += amount * d[a];
  }
  for (double& v : f) {
    v = std::clamp(v, -1.0, 1.0);
    if (std::abs(v) < 1e-12) v = 0;  // sin(180 degrees) is 1e-16, not 0
  }
  return f;
}

void HidPidDevice::expire(Clock::time_point now) {
  if (paused_) return;  // time stands still for paused effects
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    Effect& e = blocks_[i];
    if (!e.allocated || !e.playing || !e.duration_s || e.loops <= 0) continue;
    const double played = std::chrono::duration<double>(now - e.started).count() - e.start_delay_s;
    if (played >= *e.duration_s * e.loops) {
      e.playing = false;
      queue_input(pid_state_report(static_cast<int>(i + 1)));
    }
  }
}

void HidPidDevice::refresh(Clock::time_point now) {
  expire(now);
  const std::array<double, 2> f = force_locked();
  for (std::size_t a = 0; a < 2; ++a) {
    const std::int16_t t = to_torque(f[a]);
    if (t == torque_[a]) continue;
    torque_[a] = t;
    ++torque_updates_[a];
    updates_.push_back(TorqueUpdate{static_cast<int>(a), t, now});
  }
}

// ---- effect blocks ----

HidPidDevice::Effect* HidPidDevice::block(std::int64_t index) {
  if (index < 1 || index > static_cast<std::int64_t>(blocks_.size())) return nullptr;
  Effect& e = blocks_[static_cast<std::size_t>(index - 1)];
  return e.allocated ? &e : nullptr;
}

int HidPidDevice::blocks_in_use() const {
  return static_cast<int>(std::count_if(blocks_.begin(), blocks_.end(), [](const Effect& e) { return e.allocated; }));
}

// What one effect block holds in the device's RAM, in bytes, for the pool figures: its Set Effect
// parameters and the largest type-specific parameter block (each report's data, without its ID).
std::size_t HidPidDevice::ram_per_block() const {
  const std::size_t id = descriptor_.uses_report_ids ? 1 : 0;
  std::size_t params = 0;
  for (std::uint32_t u : kParameterReports) {
    const Report r = find_report(ReportType::Output, u);
    if (r.present) params = std::max(params, r.bytes - id);
  }
  return set_effect_.bytes - id + params;
}

// Create New Effect (pid1_01, Create New Effect Report, a Feature report the host sets): the
// device allocates an effect block of the type, and the host reads the outcome with Block Load.
void HidPidDevice::create_new_effect(std::span<const std::uint8_t> data) {
  last_created_.reset();
  const Field type = find(ReportType::Feature, create_effect_.id, kEffectType);
  const std::optional<std::uint32_t> u = type ? type.field->array_usage(get(data, type)) : std::nullopt;
  if (!u) {
    last_load_ = LoadStatus::Error;
    return;
  }
  for (std::size_t i = 0; i < blocks_.size(); ++i)
    if (!blocks_[i].allocated) {
      blocks_[i] = Effect{};
      blocks_[i].allocated = true;
      blocks_[i].type = *u;
      last_created_ = static_cast<int>(i + 1);
      last_load_ = LoadStatus::Success;
      return;
    }
  last_load_ = LoadStatus::Full;
}

// Block Load (pid1_01, PID Block Load Report): the block the last Create New Effect got (0, no
// block, unless it succeeded), Success / Full / Error, and the RAM left. Error also when no Create
// New Effect came before. The FF2 declares RAM Pool Available as an Array field with the one usage;
// its value is the byte count all the same.
std::vector<std::uint8_t> HidPidDevice::block_load() const {
  std::vector<std::uint8_t> r(block_load_.bytes, 0);
  if (descriptor_.uses_report_ids) r[0] = block_load_.id;
  put(r, find(ReportType::Feature, block_load_.id, kEffectBlockIndex), last_created_.value_or(0));
  if (const Field status = find(ReportType::Feature, block_load_.id, kBlockLoadStatus)) {
    const std::uint32_t u = last_load_ == LoadStatus::Success ? kBlockLoadSuccess
                            : last_load_ == LoadStatus::Full  ? kBlockLoadFull
                                                              : kBlockLoadError;
    put(r, status, status.field->array_value(u).value_or(0));
  }
  if (const Field ram = find(ReportType::Feature, block_load_.id, kRamPoolAvailable)) {
    const auto free_blocks = blocks_.size() - static_cast<std::size_t>(blocks_in_use());
    put(r, ram, std::min<std::int64_t>(static_cast<std::int64_t>(free_blocks * ram_per_block()), ram.field->logical_max));
  }
  return r;
}

// PID Pool (pid1_01, PID Pool Report): RAM Pool Size for all the blocks; every block can play at
// once (Simultaneous Effects Max = the block count); Device Managed Pool set, since the device
// allocates blocks itself (Create New Effect / Block Load) and the host never places parameter
// blocks by offset; Shared Parameter Blocks clear: each effect has its own parameters.
std::vector<std::uint8_t> HidPidDevice::pid_pool() const {
  std::vector<std::uint8_t> r(pool_.bytes, 0);
  if (descriptor_.uses_report_ids) r[0] = pool_.id;
  if (const Field f = find(ReportType::Feature, pool_.id, kRamPoolSize))
    put(r, f, std::min<std::int64_t>(static_cast<std::int64_t>(blocks_.size() * ram_per_block()), f.field->logical_max));
  if (const Field f = find(ReportType::Feature, pool_.id, kSimultaneousEffectsMax))
    put(r, f, std::min<std::int64_t>(static_cast<std::int64_t>(blocks_.size()), f.field->logical_max));
  put(r, find(ReportType::Feature, pool_.id, kDeviceManagedPool), 1);
  put(r, find(ReportType::Feature, pool_.id, kSharedParameterBlocks), 0);
  return r;
}

// ---- output reports ----

void HidPidDevice::handle_output(std::span<const std::uint8_t> report) {
  const std::uint8_t id = descriptor_.uses_report_ids ? (report.empty() ? 0 : report.front()) : 0;
  const std::span<const std::uint8_t> data = payload(report);
  if (id == set_effect_.id) set_effect(id, data);
  else if (id == set_cf_.id) set_constant_force(id, data);
  else if (id == effect_op_.id) effect_operation(id, data);
  else if (block_free_.present && id == block_free_.id) block_free(id, data);
  else if (device_control_.present && id == device_control_.id) device_control(id, data);
  else if (gain_report_.present && id == gain_report_.id) device_gain(id, data);
  else if (descriptor_.report_bytes(ReportType::Output, id) == 0) ++rejected_;
  // Other PID reports (envelope, condition, periodic, ramp, custom force): taken, not modelled.
}

// Set Effect (pid1_01, Set Effect Report): the effect's type, duration, gain, trigger, axes and
// direction. Durations with a value outside the logical range (the null value 0xFFFF, all bits
// set) are infinite. Trigger Button and Trigger Repeat Interval are kept by no one: the model's
// buttons never press.
void HidPidDevice::set_effect(std::uint8_t id, std::span<const std::uint8_t> data) {
  Effect* e = block(get(data, find(ReportType::Output, id, kEffectBlockIndex)));
  if (!e) {
    ++rejected_;
    return;
  }
  if (const Field f = find(ReportType::Output, id, kEffectType))
    if (const auto u = f.field->array_usage(get(data, f))) e->type = *u;
  if (const Field f = find(ReportType::Output, id, kDuration)) {
    const std::int64_t v = get(data, f);
    e->duration_s.reset();
    if (v >= f.field->logical_min && v <= f.field->logical_max) e->duration_s = f.field->physical(v);
  }
  if (const Field f = find(ReportType::Output, id, kStartDelay)) {
    const std::int64_t v = get(data, f);
    e->start_delay_s = v >= f.field->logical_min && v <= f.field->logical_max ? f.field->physical(v) : 0.0;
  }
  if (const Field f = find(ReportType::Output, id, kGain))
    e->gain = std::clamp(static_cast<double>(get(data, f)) / gain_max_, 0.0, 1.0);
  const Field x = find(ReportType::Output, id, kX, kAxesEnable), y = find(ReportType::Output, id, kY, kAxesEnable);
  e->axes_enabled[0] = x ? get(data, x) != 0 : true;
  e->axes_enabled[1] = y ? get(data, y) != 0 : true;
  if (const Field f = find(ReportType::Output, id, kDirectionEnable)) e->direction_enabled = get(data, f) != 0;
  if (const Field f = find(ReportType::Output, id, kOrdinal1, kDirection)) e->direction_deg = f.field->physical(get(data, f));
}

// Set Constant Force (pid1_01, Set Constant Force Report): Magnitude, signed, as a fraction of its
// logical maximum.
void HidPidDevice::set_constant_force(std::uint8_t id, std::span<const std::uint8_t> data) {
  Effect* e = block(get(data, find(ReportType::Output, id, kEffectBlockIndex)));
  const Field m = find(ReportType::Output, id, kMagnitude);
  if (!e || !m) {
    ++rejected_;
    return;
  }
  e->magnitude = std::clamp(static_cast<double>(get(data, m)) / magnitude_max_, -1.0, 1.0);
}

// Effect Operation (pid1_01, Effect Operation Report): Start (from the beginning), Start Solo (and
// stop every other effect), Stop. Loop Count plays the duration that many times; the model reads 0
// as once and the field's logical maximum as forever (DirectInput's INFINITE iterations).
void HidPidDevice::effect_operation(std::uint8_t id, std::span<const std::uint8_t> data) {
  const std::int64_t index = get(data, find(ReportType::Output, id, kEffectBlockIndex));
  Effect* e = block(index);
  const Field op = find(ReportType::Output, id, kEffectOperation);
  const std::optional<std::uint32_t> u = op ? op.field->array_usage(get(data, op)) : std::nullopt;
  if (!e || !u) {
    ++rejected_;
    return;
  }
  if (*u == kOpEffectStop) {
    e->playing = false;
  } else if (*u == kOpEffectStart || *u == kOpEffectStartSolo) {
    if (*u == kOpEffectStartSolo)
      for (Effect& other : blocks_) other.playing = false;
    e->playing = true;
    e->started = Clock::now();
    e->loops = 1;
    if (const Field loops = find(ReportType::Output, id, kLoopCount)) {
      const std::int64_t n = get(data, loops);
      e->loops = n >= loops.field->logical_max ? 0 : static_cast<int>(std::max<std::int64_t>(n, 1));
    }
  }
  queue_input(pid_state_report(static_cast<int>(index)));
}

// Block Free (pid1_01, PID Block Free Report): the block is stopped and given back to the pool.
void HidPidDevice::block_free(std::uint8_t id, std::span<const std::uint8_t> data) {
  Effect* e = block(get(data, find(ReportType::Output, id, kEffectBlockIndex)));
  if (!e) {
    ++rejected_;
    return;
  }
  *e = Effect{};
}

// Device Control (pid1_01, PID Device Control Report): an Array whose value selects one command
// (the FF2: 8 bits, 1..6 for Enable Actuators .. Device Continue; hid-pidff writes the command's
// 1-based index), or one bit per command in the Variable form.
void HidPidDevice::device_control(std::uint8_t id, std::span<const std::uint8_t> data) {
  bool any = false;
  for (const ReportField& f : descriptor_.fields) {
    if (f.type != ReportType::Output || f.report_id != id || f.constant) continue;
    for (std::size_t i = 0; i < f.count; ++i) {
      const std::int64_t v = hid::read_field(data, f, i);
      if (!f.variable) {
        if (const auto u = f.array_usage(v)) {
          device_control_command(*u);
          any = true;
        }
      } else if (v != 0) {
        device_control_command(f.element_usage(i));
        any = true;
      }
    }
  }
  if (!any) ++rejected_;
}

// The commands as pid1_01 defines them: Enable/Disable Actuators switch the force output (the
// effects keep playing meanwhile), Stop All Effects stops every effect, Device Reset frees every
// effect block, clears a pause and enables the actuators, Pause freezes every effect where it is
// and Continue resumes the paused effects from there.
void HidPidDevice::device_control_command(std::uint32_t command) {
  const auto now = Clock::now();
  if (command == kDcEnableActuators) {
    actuators_enabled_ = true;
  } else if (command == kDcDisableActuators) {
    actuators_enabled_ = false;
  } else if (command == kDcStopAllEffects) {
    for (Effect& e : blocks_) e.playing = false;
  } else if (command == kDcDeviceReset) {
    for (Effect& e : blocks_) e = Effect{};
    last_created_.reset();
    paused_ = false;
    actuators_enabled_ = true;
  } else if (command == kDcDevicePause) {
    if (!paused_) paused_at_ = now;
    paused_ = true;
  } else if (command == kDcDeviceContinue) {
    if (paused_)
      for (Effect& e : blocks_)
        if (e.playing) e.started += now - paused_at_;
    paused_ = false;
  } else {
    ++rejected_;
    return;
  }
  queue_input(pid_state_report(0));
}

// Device Gain (pid1_01, Device Gain Report): scales every effect, as a fraction of its logical maximum.
void HidPidDevice::device_gain(std::uint8_t id, std::span<const std::uint8_t> data) {
  const Field g = find(ReportType::Output, id, kDeviceGain);
  if (!g) {
    ++rejected_;
    return;
  }
  device_gain_ = std::clamp(static_cast<double>(get(data, g)) / device_gain_max_, 0.0, 1.0);
}

// ---- input reports ----

// The position report: X and Y from the hand, every other field at rest: 0 where the logical range
// holds it (buttons released, Rz and the slider at 0), a field with a Null State (the hat) at a
// value outside its logical range, its null (HID 1.11 section 6.2.2.5), else its logical minimum.
std::vector<std::uint8_t> HidPidDevice::joystick_report() const {
  std::vector<std::uint8_t> r(input_.bytes, 0);
  if (descriptor_.uses_report_ids) r[0] = input_.id;
  const std::span<std::uint8_t> data = descriptor_.uses_report_ids ? std::span<std::uint8_t>(r).subspan(1) : std::span<std::uint8_t>(r);
  for (const ReportField& f : descriptor_.fields) {
    if (f.type != ReportType::Input || f.report_id != input_.id || f.constant) continue;
    for (std::size_t i = 0; i < f.count; ++i) {
      std::int64_t v = 0;
      const bool is_x = &f == x_.field && i == x_.element, is_y = &f == y_.field && i == y_.element;
      if (is_x || is_y) {
        // -1..+1 over the whole logical range, as the host maps it back (centre (min + max) / 2).
        const double fraction = position_[is_x ? 0 : 1];
        v = static_cast<std::int64_t>(std::floor(f.logical_min + (fraction + 1) / 2 * (static_cast<double>(f.logical_max) - f.logical_min) + 0.5));
      } else if (!f.variable) {
        v = 0;  // an Array element 0 outside the logical range: no usage
      } else if (f.null_state) {
        v = ~std::int64_t{0};  // all bits set: outside the FF2 hat's 0..7
      } else if (!(f.logical_min <= 0 && 0 <= f.logical_max)) {
        v = f.logical_min;
      }
      hid::write_field(data, f, v, i);
    }
  }
  return r;
}

// PID State (pid1_01, PID State Report): the device's switches and whether `block` (0: none) plays.
// The model has no safety switch or override switch to read: the safety switch reads closed (a
// hand on the stick), the override switch open.
std::vector<std::uint8_t> HidPidDevice::pid_state_report(int block_index) const {
  if (!pid_state_.present) return {};
  std::vector<std::uint8_t> r(pid_state_.bytes, 0);
  if (descriptor_.uses_report_ids) r[0] = pid_state_.id;
  const auto id = pid_state_.id;
  put(r, find(ReportType::Input, id, kDevicePaused), paused_);
  put(r, find(ReportType::Input, id, kActuatorsEnabled), actuators_enabled_);
  put(r, find(ReportType::Input, id, kSafetySwitch), 1);
  put(r, find(ReportType::Input, id, kActuatorOverrideSwitch), 0);
  put(r, find(ReportType::Input, id, kActuatorPower), actuators_enabled_ && !paused_);
  const bool playing = block_index >= 1 && block_index <= static_cast<int>(blocks_.size()) &&
                       blocks_[static_cast<std::size_t>(block_index - 1)].allocated &&
                       blocks_[static_cast<std::size_t>(block_index - 1)].playing;
  put(r, find(ReportType::Input, id, kEffectPlaying), playing);
  put(r, find(ReportType::Input, id, kEffectBlockIndex), std::max(block_index, 0));
  return r;
}

}  // namespace sandpaper::usb_lab
