#pragma once
// USB HID PID force-feedback joysticks present on this machine (docs/USB_PID.md): found through
// libusb and matched to the device calibrations that name their IDs. Shared by `sandpaper devices`,
// `sandpaper run --device usb` and `sandpaper-play --device usb`.
#include <ostream>
#include <string>
#include <vector>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/runtime/usb/libusb_transport.hpp"

namespace sandpaper::cli {

struct Found {
  runtime::usb::UsbHidDeviceInfo info;
  const calibration::DeviceCalibration* calibration = nullptr;  // nullptr: PID device we have no calibration for
};

// "1209:ffb0"
std::string ids(int vendor, int product);
// The udev rule that gives the logged-in user the device, and how to load it.
void print_udev_help(std::ostream& out, int vendor, int product);
// "openffboard-2axis (1209:ffb0)", or "none".
std::string known_list(const calibration::CalibrationSet& set);
// Force-feedback devices present: a PID usage in the report descriptor, or a known VID:PID.
// Returns false (after printing why on stderr, naming `command`) when USB cannot be searched or none is present.
bool find_devices(const calibration::CalibrationSet& set, std::vector<Found>& found, const char* command);
// The first device found that has a calibration; nullptr (after saying so) when none has.
const Found* first_calibrated(const std::vector<Found>& found, const char* command);

}  // namespace sandpaper::cli
