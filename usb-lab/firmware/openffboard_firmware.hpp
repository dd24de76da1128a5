#pragma once
// The OpenFFBoard firmware's 2-axis force-feedback joystick (its FFBJoystick main class with
// FFBHIDMain, HidFFB, EffectsCalculator and AxesManager/Axis), compiled for the host from
// ../shared/third_party/openffboard with shims for its RTOS, HAL, flash and USB device stack, as
// a UsbFunction. Its motor drivers and encoders are the simulated stick's: the firmware's torque
// per axis comes out here, the stick's position goes in.
#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>

#include "usb_function.hpp"

namespace sandpaper::usb_lab {

// One update of the firmware's motor drivers: the torque each axis's driver was commanded, in the
// firmware's torque units (int16, full scale +-32767 as MotorDriver::turn takes it), on the
// process's steady clock.
struct TorqueUpdate {
  int axis = 0;
  std::int16_t torque = 0;
  std::chrono::steady_clock::time_point time;
};

// What the firmware reports of its own state (for stop and fault checks).
struct FirmwareState {
  bool ffb_active = false;          // HidFFB: effects enabled (Device Control enable/disable)
  bool actuators_enabled = false;   // the axes' drivers are enabled
  int effects_in_use = 0;           // effect blocks allocated
  std::int16_t torque[2] = {0, 0};  // the last torque each axis's driver was commanded
  std::uint64_t torque_updates[2] = {0, 0};  // how many times each driver's torque was set
  // TIM_FFB's update interrupts: run, and dropped because the host ran the lab's timer thread more
  // than a period late. Their ratio says how starved the guest was, apart from what a test measures.
  std::uint64_t ffb_timer_updates = 0;
  std::uint64_t ffb_timer_updates_dropped = 0;
  std::uint64_t ffb_timer_periods_due = 0;  // periods whose update time has come (hal::TimerUpdateCounts::due)
  // Control steps the firmware ran (FFBHIDMain::Run woke). On the chip one per timer update; a step
  // that overran on the host takes up the updates that came meanwhile in one. The hand moves one
  // period per step (move_stick), so steps / (updates run + dropped) is how fast the hand really
  // moved against its nominal speed.
  std::uint64_t ffb_control_steps = 0;
};

// The firmware's main classes the lab runs (ClassIDs.h): the 2-axis joystick (FFBJoystick, class 2)
// and the 1-axis wheel (FFBWheel, class 1, with its 1-axis HID descriptor).
enum class MainClass { Joystick, Wheel };

class OpenFFBoardFirmware : public UsbFunction {
 public:
  // Constructs the firmware's main class `main` as its startup code would (chosen as on the board:
  // the flash's current config, written before the first start) and starts its threads. The
  // firmware keeps global state: one per process. Throws std::logic_error on a second call.
  static std::unique_ptr<OpenFFBoardFirmware> start(MainClass main = MainClass::Joystick);
  // The axes the main class drives (joystick 2, wheel 1); an `axis` argument is below this.
  virtual int axes() const = 0;

  // The handle's position on `axis` (0 = X, 1 = Y) as the firmware's encoder for that axis reads
  // it, as a fraction of the axis's range: -1 and +1 are the ends the firmware reports as its
  // input report's logical minimum and maximum.
  virtual void set_position(int axis, double fraction_of_range) = 0;

  // The handle's path on the firmware's own clock: as each control step wakes (FFBHIDMain::Run's
  // WaitForNotification), the encoders read path(t) (X and Y as fractions of range, as
  // set_position takes them), t in s since this call counted in the FFB timer's periods (999 Hz:
  // t advances 1001 us per step). On the chip every timer update runs one step; on the host a step
  // that overran takes up the updates that came meanwhile in one, and the hand waits for it, so
  // each step sees one period of motion, as on the chip. A hand moved on the host's clock instead
  // shows the firmware speed spikes and gaps no real stick makes. Runs on the firmware's control
  // task holding the core: it must not call this object. An empty path stops it.
  using StickPath = std::function<std::array<double, 2>(double t_s)>;
  virtual void move_stick(StickPath path) = 0;

  // Called from the firmware's thread on every driver torque update; set before configured().
  virtual void on_torque(std::function<void(const TorqueUpdate&)> observer) = 0;

  virtual FirmwareState state() const = 0;

  // The firmware's FFB update rate in Hz (its effects calculation and driver updates), as
  // compiled and configured.
  virtual double update_rate_hz() const = 0;
};

}  // namespace sandpaper::usb_lab
