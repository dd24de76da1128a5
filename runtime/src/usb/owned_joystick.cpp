#include "sandpaper/runtime/usb/owned_joystick.hpp"

namespace sandpaper::runtime::usb {

OwnedHidPidJoystick::OwnedHidPidJoystick(std::unique_ptr<UsbTransport> transport,
                                         const calibration::DeviceCalibration& calibration,
                                         const HidPidOptions& options)
    : transport_(std::move(transport)), joystick_(*transport_, calibration, options) {}

OwnedHidPidJoystick::~OwnedHidPidJoystick() { joystick_.close(); }

}  // namespace sandpaper::runtime::usb
