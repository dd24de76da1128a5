#pragma once
// A force-feedback joystick or wheel driven by the kernel and reached through its input event node
// (Linux's force-feedback interface: EVIOCSFF, EV_FF; Documentation/input/ff.rst): how SDL, Wine
// and games play them, without root and without taking the device from anyone. One FF_CONSTANT
// effect per axis with a fixed direction (X at 0x4000, Y at 0x8000), whose level is updated; position
// from ABS_X/ABS_Y scaled by their absinfo onto the calibration's workspace. docs/DEVICES.md.
#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <thread>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/runtime/device.hpp"
#include "sandpaper/runtime/evdev/evdev_node.hpp"

struct libevdev;

namespace sandpaper::runtime::evdev {

// Why the node could not be played; `error` is the errno of the call that failed (0: the device
// lacks what is needed, e.g. FF_CONSTANT).
struct EvdevError : std::runtime_error {
  EvdevError(int e, const std::string& what) : std::runtime_error(what), error(e) {}
  int error;
};

// A calibration whose command unit is this counts FF_CONSTANT levels themselves (struct
// ff_constant_effect, linux/input.h): levels go to the kernel as they are, whatever its driver.
inline constexpr const char* kLevelUnit = "FF_CONSTANT level";
// The profile (calibration/profiles/) a device without a calibration file plays with under --uncalibrated.
inline constexpr const char* kUncalibratedProfile = "uncalibrated-evdev";

// The FF_CONSTANT level (-0x8000..0x7fff) that Linux's hid-pidff turns into exactly `command` in a
// Magnitude field of logical range [logical_min, logical_max] (pidff_rescale_signed, hid-pidff.c,
// Linux 6.1: level * max / 0x7fff above zero, level * min / -0x8000 below, truncated). Requires
// logical_min < 0 < logical_max; `command` is clamped to the range.
std::int16_t level_for_command(std::int32_t command, std::int32_t logical_min, std::int32_t logical_max) noexcept;
// What hid-pidff sends for `level` (the same formula), for tests and explain.
std::int32_t command_for_level(std::int16_t level, std::int32_t logical_min, std::int32_t logical_max) noexcept;

// The level the driver asks for so that `force_N` (N, along axis `axis`) reaches the device: command
// units through the calibration's axis scale and sense, clamped to its command_max and to the
// Magnitude range [magnitude_min, magnitude_max] of the device's Set Constant Force, then through
// level_for_command; a calibration in kLevelUnit gives the level itself (the range is then the level's).
std::int16_t level_for_force(const calibration::DeviceCalibration& calibration, int axis, double force_N,
                             std::int32_t magnitude_min, std::int32_t magnitude_max) noexcept;

class EvdevJoystick final : public HeldDevice {
 public:
  // Opens `node` (read-write), sets the device gain to full and autocenter off, the position axes'
  // fuzz to 0 (hid-input filters joystick axes by 1/256 of their range), and uploads and starts one
  // zero-level effect per axis. Newtons become command units through `calibration`'s axis scales and
  // then levels through the Magnitude range of the HID device's report descriptor (sysfs), or are
  // levels already (command unit kLevelUnit, any driver). Updates go out from an I/O thread, at most
  // one per out interval (the longer of the calibration's and the node's endpoint's; 1 ms if neither
  // is known), the axes in turn, so usbhid's 64-report output queue never fills. Throws EvdevError.
  EvdevJoystick(const EvdevNode& node, const calibration::DeviceCalibration& calibration);
  ~EvdevJoystick() override;
  EvdevJoystick(const EvdevJoystick&) = delete;
  EvdevJoystick& operator=(const EvdevJoystick&) = delete;

  const DeviceLimits& limits() const noexcept override { return limits_; }
  // The latest position (m) the I/O thread decoded. False, with the fault set, once the node is
  // gone, a read failed, or the I/O thread has not cycled for 50 ms (evdev reports only changes, so
  // a handle held still is silent: it is the thread, not the device, that is watched).
  bool read_position_rt(double t_s, glm::dvec2& position_m) noexcept override;
  bool position_fresh_rt() const noexcept override { return fresh_; }
  // Publishes the force (N) for the I/O thread; false once it has failed.
  bool write_force_rt(glm::dvec2 force_N) noexcept override;
  DeviceFault last_fault_rt() const noexcept override { return fault_.load(std::memory_order_acquire); }

  // Zero level, effects stopped and erased, gain and autocenter back to the kernel's defaults
  // (0xffff both, as hid-pidff sets them when it binds: the previous values cannot be read), fuzz
  // restored, node closed. Idempotent; the destructor calls it.
  void close_nonrt() noexcept override;
  std::string fault_detail_nonrt() const override;

  // The last levels the I/O thread handed to the kernel, and how many updates it made (per axis).
  std::int16_t last_level(int axis) const noexcept { return sent_level_[static_cast<std::size_t>(axis)].load(); }
  std::uint64_t updates(int axis) const noexcept { return updates_[static_cast<std::size_t>(axis)].load(); }
  int axes() const noexcept { return axes_; }

 private:
  void fail(int error, const std::string& what);  // closes what is open, throws EvdevError
  void io_thread_body() noexcept;
  bool drain_events() noexcept;                    // false on a fault
  glm::dvec2 current_position() const noexcept;    // m
  bool update_level(int axis, std::int16_t level) noexcept;
  void set_fault(DeviceFault fault, int error) noexcept;
  std::int16_t level_of(int axis, double force_N) const noexcept;
  bool write_ff(unsigned code, int value) noexcept;

  EvdevNode node_;
  calibration::DeviceCalibration calibration_;
  DeviceLimits limits_;
  int fd_ = -1;
  libevdev* dev_ = nullptr;
  int axes_ = 0;
  unsigned abs_code_[2] = {0, 0};
  int abs_min_[2] = {0, 0}, abs_max_[2] = {0, 0}, abs_fuzz_[2] = {0, 0};
  std::int32_t magnitude_min_ = 0, magnitude_max_ = 0;
  bool levels_ = false;  // commands are FF_CONSTANT levels (kLevelUnit)
  int effect_id_[2] = {-1, -1};
  std::int64_t out_interval_ns_ = 1'000'000;
  bool closed_ = false, gain_set_ = false, autocenter_set_ = false, fuzz_set_ = false;

  std::atomic<DeviceFault> fault_{DeviceFault::None};
  std::atomic<int> fault_errno_{0};
  std::atomic<std::uint64_t> position_raw_{0};     // two floats, metres
  std::atomic<std::uint64_t> position_reports_{0};
  std::atomic<std::uint32_t> level_raw_{0};        // two int16 levels the tick wants
  std::atomic<std::int16_t> sent_level_[2] = {0, 0};
  std::atomic<std::uint64_t> updates_[2] = {0, 0};
  std::atomic<std::uint64_t> io_cycles_{0};
  std::atomic<bool> io_running_{false};
  std::uint64_t seen_reports_ = 0, seen_cycles_ = 0;  // tick side
  double last_cycle_t_s_ = 0;
  bool have_time_ = false, fresh_ = false;
  glm::dvec2 position_m_{0, 0};
  std::thread io_thread_;
};

}  // namespace sandpaper::runtime::evdev
