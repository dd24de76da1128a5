#pragma once
// The Microsoft SideWinder Force Feedback 2 joystick (USB 045E:001B) as the lab's HID PID device
// model: its recorded report descriptor (tests/runtime/usb/data/ms_sidewinder_ffb2.hex, compiled in
// at configure time) and its recorded device and endpoint descriptors (SidewinderFFPDetails.md in
// github.com/tloimu/adapt-ffb-joy, commit bc13ea5f, "Microsoft Sidewinder Force Feedback 2 Joystick
// HID Descriptor"). No firmware of the FF2 exists to run: HidPidDevice plays the class definition.
#include <cstdint>
#include <memory>
#include <span>

#include "hid_pid_device.hpp"

namespace sandpaper::usb_lab {

// The FF2's report descriptor, 1343 bytes (the recorded wDescriptorLength); defined in a source
// file CMake generates from the .hex.
std::span<const std::uint8_t> sidewinder_ff2_report_descriptor();

std::unique_ptr<HidPidDevice> sidewinder_ff2();

}  // namespace sandpaper::usb_lab
