#pragma once
// A USB HID PID joystick together with the transport it talks through (libusb or hidraw), as one Device for
// callers that keep a device for as long as they like (the studio, sandpaper::Player::usb): the
// joystick is given back (zero force, effects freed, kernel driver reattached) before the transport closes.
#include <memory>

#include "sandpaper/runtime/usb/hid_pid_joystick.hpp"
#include "sandpaper/runtime/usb/libusb_transport.hpp"

namespace sandpaper::runtime::usb {

class OwnedHidPidJoystick final : public HeldDevice {
 public:
  // Opens the joystick on `transport` (HidPidJoystick's constructor: throws HidPidError).
  OwnedHidPidJoystick(std::unique_ptr<UsbTransport> transport, const calibration::DeviceCalibration& calibration,
                      const HidPidOptions& options = {});
  ~OwnedHidPidJoystick() override;

  const DeviceLimits& limits() const noexcept override { return joystick_.limits(); }
  bool read_position_rt(double t_s, glm::dvec2& position_m) noexcept override {
    return joystick_.read_position_rt(t_s, position_m);
  }
  bool position_fresh_rt() const noexcept override { return joystick_.position_fresh_rt(); }
  bool write_force_rt(glm::dvec2 force_N) noexcept override { return joystick_.write_force_rt(force_N); }
  DeviceFault last_fault_rt() const noexcept override { return joystick_.last_fault_rt(); }
  void close_nonrt() noexcept override { joystick_.close(); }
  std::string fault_detail_nonrt() const override { return joystick_.fault_detail_nonrt(); }

  // The driver itself: its fault_status() after a run, or close() before the report is printed.
  HidPidJoystick& joystick() noexcept { return joystick_; }

 private:
  std::unique_ptr<UsbTransport> transport_;  // declared first: outlives the joystick
  HidPidJoystick joystick_;
};

}  // namespace sandpaper::runtime::usb
