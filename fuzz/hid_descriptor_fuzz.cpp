// What a USB force-feedback joystick tells the driver (runtime/usb): its HID report descriptor, then
// its replies while the driver opens it and plays (PID Pool, Block Load, position reports). The
// input is a 2-byte little-endian descriptor length, the descriptor, then replies, each a length
// byte and that many bytes, taken in order by GET_REPORT and by interrupt IN reads.
//
// Checked: a parsed descriptor keeps within hid_limits and its fields' bits round-trip; opening
// throws nothing but HidPidError; every report the driver hands the transport is at most 64 bytes and
// is read here whole (so a span past a buffer is an ASan report too); an opened joystick sends 0 for zero force, keeps every command
// within the Magnitude's logical range, and reads finite positions.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "fuzz_support.hpp"
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/runtime/usb/hid_descriptor.hpp"
#include "sandpaper/runtime/usb/hid_pid_joystick.hpp"
#include "sandpaper/runtime/usb/libusb_transport.hpp"
#include "sandpaper/runtime/usb/transport.hpp"

namespace {

using namespace sandpaper::runtime::usb;

// A device that replies from the fuzz input and reads every byte it is given.
class ScriptedTransport final : public UsbTransport {
 public:
  ScriptedTransport(std::vector<std::uint8_t> descriptor, std::span<const std::uint8_t> replies)
      : descriptor_(std::move(descriptor)), replies_(replies) {}

  UsbStatus report_descriptor(std::vector<std::uint8_t>& descriptor) override {
    descriptor = descriptor_;
    return UsbStatus::Ok;
  }
  UsbStatus detach_kernel_driver() override { return UsbStatus::Ok; }
  UsbStatus attach_kernel_driver() override { return UsbStatus::Ok; }
  UsbStatus claim_interface() override { return UsbStatus::Ok; }
  UsbStatus release_interface() override { return UsbStatus::Ok; }
  UsbStatus read_input(std::span<std::uint8_t> buffer, std::size_t& length, unsigned) noexcept override {
    return next(buffer, length) ? UsbStatus::Ok : UsbStatus::Timeout;
  }
  UsbStatus write_output(std::span<const std::uint8_t> report) noexcept override { return take(report); }
  UsbStatus set_feature(std::span<const std::uint8_t> report) override { return take(report); }
  UsbStatus get_feature(std::uint8_t, std::span<std::uint8_t> buffer, std::size_t& length) override {
    return next(buffer, length) ? UsbStatus::Ok : UsbStatus::Stalled;  // out of replies
  }

 private:
  bool next(std::span<std::uint8_t> buffer, std::size_t& length) noexcept {
    length = 0;
    if (replies_.empty()) return false;
    const std::size_t n = std::min<std::size_t>(replies_[0], replies_.size() - 1);
    length = std::min(n, buffer.size());
    std::copy_n(replies_.begin() + 1, length, buffer.begin());
    replies_ = replies_.subspan(1 + n);
    return true;
  }
  UsbStatus take(std::span<const std::uint8_t> report) noexcept {
    // The driver builds every report in a 64-byte buffer (a full-speed packet): a longer span reads
    // past it, which ASan sees below and this sees without ASan (the replay tests).
    sandpaper::fuzz::check(report.size() <= 64, "the driver handed over a report of " + std::to_string(report.size()) + " bytes");
    for (std::uint8_t b : report) sink_ = static_cast<std::uint8_t>(sink_ + b);
    return UsbStatus::Ok;
  }

  std::vector<std::uint8_t> descriptor_;
  std::span<const std::uint8_t> replies_;
  volatile std::uint8_t sink_ = 0;
};

// The shipped joystick's device file, or (wheel) the wheel's: one axis, y never sent.
const sandpaper::calibration::DeviceCalibration& device(bool wheel) {
  static const auto set = sandpaper::calibration::CalibrationSet::load(sandpaper::fuzz::source_dir() / "calibration");
  const char* name = wheel ? "openffboard-wheel" : "openffboard-2axis";
  const auto* d = set.find_device(name);
  sandpaper::fuzz::check(d != nullptr, std::string("the shipped calibration has no ") + name);
  return *d;
}

void check_descriptor(const HidReportDescriptor& d) {
  using sandpaper::fuzz::check;
  check(d.fields.size() <= hid_limits::kFields, "more fields than hid_limits::kFields");
  std::size_t array_usages = 0;
  std::vector<std::uint8_t> report;
  std::map<std::pair<ReportType, std::uint8_t>, std::size_t> report_bytes;  // report_bytes() walks every field
  for (std::size_t i = 0; i < d.fields.size(); ++i) {
    const HidField& f = d.fields[i];
    array_usages += f.array_usages.size();
    auto [at, is_new] = report_bytes.try_emplace({f.type, f.report_id}, 0);
    if (is_new) at->second = d.report_bytes(f.type, f.report_id);
    const std::size_t bytes = at->second;
    check(bytes <= hid_limits::kReportBytes, "a report over hid_limits::kReportBytes: " + std::to_string(bytes));
    check(std::size_t{f.bit_offset} + f.bit_size <= (bytes - (d.uses_report_ids ? 1 : 0)) * 8, "a field past its report");
    // The bit arithmetic, on the first fields of each descriptor (enough to vary offsets and sizes).
    if (i < 64 && f.bit_size >= 1 && f.bit_size <= 32) {
      report.assign(bytes, 0xA5);
      const std::int64_t value = f.logical_max;
      write_field(report, d.uses_report_ids, f, value);
      const std::uint64_t mask = (std::uint64_t{1} << f.bit_size) - 1;
      const auto got = static_cast<std::uint64_t>(read_field(report, d.uses_report_ids, f));
      check((got & mask) == (static_cast<std::uint64_t>(value) & mask), "write_field then read_field changed a value");
    }
  }
  check(array_usages <= hid_limits::kArrayUsages, "more array usages than hid_limits::kArrayUsages");
}

void play(HidPidJoystick& joystick) {
  using sandpaper::fuzz::check;
  const HidField* magnitude = joystick.descriptor().find(ReportType::Output, pid::kSetConstantForceReport, pid::kMagnitude);
  check(magnitude != nullptr, "an opened joystick without Magnitude");
  const double inf = std::numeric_limits<double>::infinity();
  const std::array<glm::dvec2, 5> forces = {glm::dvec2{0, 0}, {1e9, -1e9}, {inf, -inf}, {std::nan(""), 2.5}, {0, 0}};
  double t_s = 0;
  for (const auto& f : forces) {
    glm::dvec2 position_m{0, 0};
    if (joystick.read_position_rt(t_s, position_m))
      check(std::isfinite(position_m.x) && std::isfinite(position_m.y), "a non-finite position");
    t_s += 0.001;
    joystick.write_force_rt(f);
    const auto sent = joystick.last_command();
    for (std::int32_t c : sent)
      check(c >= magnitude->logical_min && c <= magnitude->logical_max,
            "a command outside Magnitude's logical range: " + std::to_string(c));
    if (f == glm::dvec2{0, 0}) check(sent[0] == 0 && sent[1] == 0, "zero force sent as " + std::to_string(sent[0]) + ", " + std::to_string(sent[1]));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const std::size_t length = std::min<std::size_t>(data[0] | (std::size_t{data[1]} << 8), size - 2);
  std::vector<std::uint8_t> descriptor(data + 2, data + 2 + length);
  const std::span<const std::uint8_t> replies(data + 2 + length, size - 2 - length);

  try {
    check_descriptor(parse_hid_report_descriptor(descriptor));
  } catch (const HidDescriptorError&) {
    return 0;  // the driver refuses the device with this message (HidPidError)
  }
  // What `sandpaper devices` reads of it, and the device file it would then pick.
  sandpaper::runtime::usb::UsbHidDeviceInfo info;
  sandpaper::runtime::usb::summarise_report_descriptor(descriptor, info);
  sandpaper::fuzz::check(info.descriptor_read && info.force_axes >= 0 && info.force_axes <= 2,
                         "a parsed descriptor summarised as unread or with " + std::to_string(info.force_axes) + " force axes");
  // Opened as the file it would be matched with (a wheel's when its effects act on X alone).
  ScriptedTransport transport(std::move(descriptor), replies);
  HidPidOptions options;
  options.io = HidPidIo::CallingThread;
  options.open_read_timeout_ms = 1;
  try {
    HidPidJoystick joystick(transport, device(info.force_axes == 1), options);
    play(joystick);
  } catch (const HidPidError&) {
  }
  return 0;
}
