#pragma once
// What the servo loop needs of a force-feedback device. Functions ending _rt run on the servo
// thread and must not allocate, lock, log or do I/O; _nonrt ones run anywhere else.
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

// Why a device call failed, so that the servo loop can name the stop cause. A driver that can tell
// (a USB driver: LIBUSB_ERROR_TIMEOUT, LIBUSB_ERROR_NO_DEVICE) overrides last_fault_rt().
enum class DeviceFault {
  None,          // no fault, or the driver cannot tell: the loop names the call that failed
  ReadFailed,    // a read returned an error
  ReadTimedOut,  // no position arrived in time
  Unplugged,     // the device is gone (read or write)
  WriteFailed,   // a force command was not accepted
};

class Device {
 public:
  virtual ~Device() = default;
  virtual const DeviceLimits& limits() const noexcept = 0;
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
};

// A device a person holds, reached through a driver that must give it back: a USB HID PID joystick
// (libusb or hidraw), an input event device. Whoever opened it closes it before reporting a run.
class HeldDevice : public Device {
 public:
  // Zero force, effects freed, the device given back as it was found (kernel driver reattached,
  // gain and autocenter restored). Best effort and idempotent; not on the servo thread.
  virtual void close_nonrt() noexcept = 0;
  // The transport's own words for the fault last_fault_rt() names ("no device", "ENODEV: No such
  // device"), or "" when there was none.
  virtual std::string fault_detail_nonrt() const = 0;
};

}  // namespace sandpaper::runtime
