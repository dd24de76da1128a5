#pragma once
// What the servo loop needs of a force-feedback device. Functions ending _rt run on the servo
// thread and must not allocate, lock, log or do I/O; _nonrt ones run anywhere else.
#include <cstdint>
#include <functional>
#include <string>

#include <glm/vec2.hpp>

namespace sandpaper::runtime {

// Device limits as data, SI units (compare CHAI3D's cHapticDeviceInfo).
struct DeviceLimits {
  std::string name;              // e.g. "sim"
  double max_force_N = 10.0;     // magnitude of the lateral force vector never exceeds this
  double min_rate_hz = 900.0;    // servo rates the device supports
  double max_rate_hz = 10000.0;
  double workspace_radius_m = 0.1143;  // thesis Table 2: 9 inch circle
};

// The force commands a device takes. A historical device's (sandpaper-1995, Minsky 1995 Table 6:
// 4.814 mN per unit, 12-bit commands) are whole steps per axis; the servo loop rounds its commands to
// them after the ramp and the clamp, so its telemetry and traces show what was sent. 0: continuous.
struct CommandQuantum {
  double step_N[2] = {0, 0};  // newtons per command unit, x and y
  long max_steps = 0;         // largest command magnitude per axis, in units (0: only the force limit)
};

// How force tables (gratings, height fields) are read between their samples.
enum class TableSampling : std::uint8_t {
  Interpolate,  // linear along a grating, bilinear over a height field (the default)
  Hold,         // the nearest sample, held: the thesis' joystick (Appendix B 2.1), `--device sandpaper-1995`
};

// Why a device call failed, so that the servo loop can name the stop cause. A driver that can tell
// (a USB driver: LIBUSB_ERROR_TIMEOUT, LIBUSB_ERROR_NO_DEVICE) overrides last_fault_rt().
enum class DeviceFault {
  None,          // no fault, or the driver cannot tell: the loop names the call that failed
  ReadFailed,    // a read returned an error
  ReadTimedOut,  // no position arrived in time
  Unplugged,     // the device is gone (read or write)
  WriteFailed,   // a force command was not accepted
};

// A device describes itself (compare CHAI3D's cGenericHapticDevice): its limits, the commands it
// takes, how the tables it plays are sampled, which clocks it can follow and why it failed. Whoever
// plays it (runtime::LiveServo, run_servo_loop) asks it, so an emulated device is the same device on
// every host and clock.
class Device {
 public:
  virtual ~Device() = default;
  virtual const DeviceLimits& limits() const noexcept = 0;
  // Whole command steps the loop rounds its forces to; default continuous.
  virtual CommandQuantum command_quantum() const noexcept { return {}; }
  // How force sources built for this device read their tables; default interpolated.
  virtual TableSampling table_sampling() const noexcept { return TableSampling::Interpolate; }
  // Whether the device can follow simulated time (VirtualClock): a simulated one can; one a person
  // holds moves in real time only.
  virtual bool follows_virtual_clock() const noexcept { return true; }
  // Position of the handle (m, patch coordinates) at servo time t_s (s since the loop started).
  // Returns false if the device could not be read.
  virtual bool read_position_rt(double t_s, glm::dvec2& position_m) noexcept = 0;
  // Whether the position the last successful read_position_rt returned is one the device reported
  // since the read before (a USB joystick's input report), not the previous one held. The loop
  // differentiates velocity between fresh positions, over the time between them. Default: every read is.
  virtual bool position_fresh_rt() const noexcept { return true; }
  // Commands the lateral force (N) for this tick. Returns false on a device fault.
  virtual bool write_force_rt(glm::dvec2 force_N) noexcept = 0;
  // Why the last read_position_rt or write_force_rt that returned false failed. Called by the loop
  // right after such a call, on the servo thread; must not allocate, lock or do I/O.
  virtual DeviceFault last_fault_rt() const noexcept { return DeviceFault::None; }
  // After a run that stopped because the device left the bus: whether it is back at the same place
  // within `within_s` (s) — a reset (a rebooted firmware), not an unplug. May wait that long; not on
  // the servo thread. Default: never (a simulated device does not leave).
  virtual bool came_back_nonrt(double within_s) {
    (void)within_s;
    return false;
  }
};

// A device a person holds, reached through a driver that must give it back: a USB HID PID joystick
// (libusb or hidraw), an input event device. Whoever opened it closes it before reporting a run.
class HeldDevice : public Device {
 public:
  bool follows_virtual_clock() const noexcept override { return false; }
  // Zero force, effects freed, the device given back as it was found (kernel driver reattached,
  // gain and autocenter restored). Best effort and idempotent; not on the servo thread.
  virtual void close_nonrt() noexcept = 0;
  // The transport's own words for the fault last_fault_rt() names ("no device", "ENODEV: No such
  // device"), or "" when there was none.
  virtual std::string fault_detail_nonrt() const = 0;
  // Gives the device back (close_nonrt), then asks the check the device factory installed.
  bool came_back_nonrt(double within_s) override {
    close_nonrt();
    return came_back_ && came_back_(within_s);
  }
  // Installed by the device factory when it opens the device, with where the device sits read then,
  // before it can go (devices/usb_port.hpp: the same IDs at the same USB port under a new address).
  void watch_for_return_nonrt(std::function<bool(double within_s)> came_back) { came_back_ = std::move(came_back); }

 private:
  std::function<bool(double)> came_back_;
};

}  // namespace sandpaper::runtime
