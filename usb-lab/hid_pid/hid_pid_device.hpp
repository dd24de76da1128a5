#pragma once
// A USB HID PID 1.0 force-feedback joystick written from the class definition ("Device Class
// Definition for Physical Interface Devices (PID) Version 1.0", usb.org pid1_01.pdf; HID 1.11), as
// a UsbFunction for the lab's FunctionFS front end: any PID report descriptor behind it, its
// reports found by their PID usages (never by report ID numbers). It models what the host can see
// of a device's effects: the effect blocks (Create New Effect, Block Load, Block Free, PID Pool),
// their parameters (Set Effect, Set Constant Force), their playback (Effect Operation, Device
// Control, Device Gain) and the force each axis would get. Only Constant Force effects produce a
// force; the other types are allocated, set and played as blocks, with no force.
#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "openffboard_firmware.hpp"  // TorqueUpdate (the header alone: the firmware is not linked)
#include "report_descriptor.hpp"
#include "usb_function.hpp"

namespace sandpaper::usb_lab {

// The interrupt endpoints the device declares (USB 2.0 section 9.6.6): full-speed bInterval in
// frames (1 ms each), wMaxPacketSize in bytes.
struct InterruptEndpoints {
  std::uint8_t in_interval = 1, out_interval = 1;
  std::uint16_t in_max_packet = 64, out_max_packet = 64;
};

struct HidPidDeviceState {
  bool actuators_enabled = false;  // Device Control Enable / Disable Actuators (and Reset)
  bool paused = false;             // Device Control Pause / Continue
  int effects_in_use = 0;          // effect blocks allocated
  int effects_playing = 0;         // allocated blocks started and not stopped or run out
  double device_gain = 1.0;        // Device Gain as a fraction of its logical maximum
  std::int16_t torque[2] = {0, 0};             // the last torque per axis (X, Y), TorqueUpdate units
  std::uint64_t torque_updates[2] = {0, 0};    // how many times each axis's torque changed
  std::uint64_t reports_rejected = 0;          // output/feature reports for unknown reports or free blocks
};

class HidPidDevice : public UsbFunction {
 public:
  // Parses `report_descriptor` (throws std::invalid_argument if it does not parse, or
  // std::runtime_error if it lacks a report the model needs: Set Effect, Set Constant Force,
  // Effect Operation, Create New Effect, Block Load, an input report with X and Y). The device
  // serves one HID interface (class 0x03, no boot subclass) with an interrupt IN and OUT endpoint.
  HidPidDevice(DeviceIdentity identity, std::vector<std::uint8_t> report_descriptor, InterruptEndpoints endpoints,
               std::uint16_t bcd_hid = 0x0111);

  DeviceIdentity identity() const override { return identity_; }
  std::vector<std::uint8_t> function_descriptors() const override;
  void configured() override;
  void deconfigured() override;
  void suspended(bool suspended) override;
  bool accepts(const SetupPacket& setup) const override;
  ControlReply control(const SetupPacket& setup, std::span<const std::uint8_t> out_data) override;
  void interrupt_out(std::span<const std::uint8_t> data) override;
  // Input reports are sent when their content changes (and once when the host configures the
  // device), plus every idle period once the host set one with SET_IDLE: HID 1.11 section 7.2.4
  // recommends an infinite idle rate (report on change only) as a joystick's default. One report
  // per report ID waits at a time, the newest: a device holds its current state, not a history.
  bool next_interrupt_in(std::vector<std::uint8_t>& report, std::chrono::microseconds wait) override;
  void interrupt_in_done(bool delivered) override;

  // The handle's position on `axis` (0 = X, 1 = Y) as a fraction of the input report's logical
  // range: -1 is its logical minimum, +1 its logical maximum.
  void set_position(int axis, double fraction_of_range);

  // Called on every change of an axis's torque, with the lock released, from whichever thread
  // caused it (a report, update(), set_position). torque = round(force fraction x 32767), POSITIVE
  // when the handle is pushed toward the axis's positive end (X: right, Y: toward the user, as the
  // input report's X and Y increase). Set before configured(); the observer must not call back.
  void on_torque(std::function<void(const TorqueUpdate&)> observer);

  // Ends effects whose duration ran out (on the steady clock) and recomputes the forces; every
  // report and set_position does the same.
  void update();

  // The force on X and Y as fractions of full scale (each clamped to -1..1): the sum over every
  // playing Constant Force effect of magnitude / Magnitude's logical maximum x effect gain x
  // device gain, projected by the effect's direction (hid_pid_device.cpp, direction_vector); zero
  // with the actuators disabled or the device paused. Positive: toward the axis's positive end.
  std::array<double, 2> force() const;

  HidPidDeviceState state() const;
  const hid::ReportDescriptor& descriptor() const { return descriptor_; }
  std::size_t effect_blocks() const { return blocks_.size(); }

 private:
  using Clock = std::chrono::steady_clock;
  struct Field {
    const hid::ReportField* field = nullptr;
    std::size_t element = 0;
    explicit operator bool() const { return field != nullptr; }
  };
  struct Effect {
    bool allocated = false;
    std::uint32_t type = 0;  // PID effect type usage (ET Constant Force, ...)
    std::optional<double> duration_s;  // nullopt: infinite
    double start_delay_s = 0;
    double gain = 1.0;
    bool axes_enabled[2] = {true, true};
    bool direction_enabled = true;
    double direction_deg = 0;
    double magnitude = 0;  // fraction of Magnitude's logical maximum, signed
    bool playing = false;
    Clock::time_point started;
    int loops = 1;
  };
  struct Report {  // a report the model handles: its ID and byte length
    std::uint8_t id = 0;
    std::size_t bytes = 0;
    bool present = false;
  };

  Report find_report(hid::ReportType type, std::uint32_t report_usage) const;
  Field find(hid::ReportType type, std::uint8_t id, std::uint32_t u, std::uint32_t parent = 0) const;
  std::int64_t get(std::span<const std::uint8_t> data, Field f) const;
  void put(std::span<std::uint8_t> data, Field f, std::int64_t value) const;
  std::span<const std::uint8_t> payload(std::span<const std::uint8_t> report) const;

  // Each returns with mutex_ held by the caller.
  void handle_output(std::span<const std::uint8_t> report);
  void set_effect(std::uint8_t id, std::span<const std::uint8_t> data);
  void set_constant_force(std::uint8_t id, std::span<const std::uint8_t> data);
  void effect_operation(std::uint8_t id, std::span<const std::uint8_t> data);
  void block_free(std::uint8_t id, std::span<const std::uint8_t> data);
  void device_control(std::uint8_t id, std::span<const std::uint8_t> data);
  void device_control_command(std::uint32_t command);
  void device_gain(std::uint8_t id, std::span<const std::uint8_t> data);
  void create_new_effect(std::span<const std::uint8_t> data);
  std::vector<std::uint8_t> block_load() const;
  std::vector<std::uint8_t> pid_pool() const;
  std::vector<std::uint8_t> joystick_report() const;
  std::vector<std::uint8_t> pid_state_report(int block) const;
  Effect* block(std::int64_t index);
  int blocks_in_use() const;
  std::size_t ram_per_block() const;
  void expire(Clock::time_point now);
  std::array<double, 2> force_locked() const;
  // Recomputes the force and queues the TorqueUpdates of the axes whose torque changed.
  void refresh(Clock::time_point now);
  // refresh(now), then hands the queued torque changes to the observer with `lock` released.
  void refresh_and_notify(std::unique_lock<std::mutex>& lock, Clock::time_point now);
  void queue_input(std::vector<std::uint8_t> report);
  void flush_updates();

  DeviceIdentity identity_;
  std::vector<std::uint8_t> descriptor_bytes_;
  hid::ReportDescriptor descriptor_;
  InterruptEndpoints endpoints_;
  std::uint16_t bcd_hid_;

  // Reports by PID usage (pid1_01 section 5 names them), resolved once.
  Report input_, pid_state_, set_effect_, set_cf_, effect_op_, block_free_, device_control_, gain_report_;
  Report create_effect_, block_load_, pool_;
  Field x_, y_;
  double magnitude_max_ = 1, gain_max_ = 1, device_gain_max_ = 1;

  mutable std::mutex mutex_;
  std::condition_variable input_ready_;
  std::vector<Effect> blocks_;  // block index i + 1
  std::optional<int> last_created_;  // Block Load's answer: the block the last Create New Effect got
  enum class LoadStatus { Success, Full, Error } last_load_ = LoadStatus::Error;
  bool actuators_enabled_ = false, paused_ = false, configured_ = false;
  Clock::time_point paused_at_;
  double device_gain_ = 1.0;
  std::array<double, 2> position_{0, 0};
  std::array<std::int16_t, 2> torque_{0, 0};
  std::array<std::uint64_t, 2> torque_updates_{0, 0};
  std::uint64_t rejected_ = 0;
  std::map<std::uint8_t, std::vector<std::uint8_t>> pending_in_;  // by report ID: the newest
  std::vector<std::uint8_t> in_flight_;
  std::uint8_t idle_4ms_ = 0;  // SET_IDLE duration, 4 ms units; 0: infinite
  Clock::time_point last_input_sent_;
  std::vector<TorqueUpdate> updates_;  // queued under the lock, delivered after it
  std::function<void(const TorqueUpdate&)> observer_;
  std::mutex observer_mutex_;  // keeps updates in order across threads
};

}  // namespace sandpaper::usb_lab
