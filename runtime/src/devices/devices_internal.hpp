#pragma once
// The factory entries that live in files of their own.
#include <cstdint>
#include <memory>
#include <string>

#include "sandpaper/runtime/devices/open_device.hpp"
#include "sandpaper/runtime/usb/transport.hpp"

namespace sandpaper::runtime {

// `v` as printf's %g writes it (these files use no formatting library: the installed package's
// dependencies stay as they are).
std::string g_text(double v);

// USB HID PID joysticks: `usb`, or a calibration with a [usb] table not asked to be simulated.
bool serves_usb(const DeviceSpec& spec, const calibration::DeviceCalibration* cal);
OpenedDevice open_usb(const calibration::CalibrationSet& set, DeviceSpec& spec, const calibration::DeviceCalibration* cal);
// The calibration of the joystick open_usb would open (searching USB, opening nothing).
std::string usb_calibration(const calibration::CalibrationSet& set, const DeviceSpec& spec,
                            const calibration::DeviceCalibration* cal);

// The HID PID driver opened on `transport` for `cal`, as the usb and hidraw entries open it: `what`
// names the device in an error ("1209:ffb0 (openffboard-2axis)"), `access_help` follows an access error.
OpenedDevice open_hid_pid(std::unique_ptr<usb::UsbTransport> transport, const calibration::DeviceCalibration& cal,
                          const DeviceSpec& spec, const std::string& what, const std::string& access_help);

// The calibration whose [usb] table names this USB device, or nullptr (also for a device not on USB).
// Where several files name one ID (a board's joystick and wheel), the one whose force axes are
// `force_axes` (read from the report descriptor: UsbHidDeviceInfo::force_axes; 0 when not read:
// the first by file name). A device whose axes no file for its ID has gets none.
const calibration::DeviceCalibration* usb_calibration_of(const calibration::CalibrationSet& set, bool on_usb,
                                                         int vendor, int product, int force_axes = 0);

namespace evdev {
struct EvdevNode;
}
// The axes an event node's force effects act on, from its HID device's report descriptor
// (UsbHidDeviceInfo::force_axes); 0 when it is not a HID PID device or cannot be read.
int force_axes_of(const evdev::EvdevNode& node);

// A joystick reached through a node of the kernel's (hidraw, an input event node): where it is.
void set_node(OpenedDevice& out, std::uint16_t vendor, std::uint16_t product, const std::string& name, const std::string& path,
              const char* transport);

// A device a person moves refuses the simulated hands (a replay, the dynamic hand) and the virtual clock.
void refuse_simulated_hands(const DeviceSpec& spec);

// HID PID joysticks through hidraw, the kernel's driver left bound: `hidraw` or `hidraw:PATH`.
bool is_hidraw_device(const std::string& device);
bool serves_hidraw(const DeviceSpec& spec, const calibration::DeviceCalibration* cal);
OpenedDevice open_hidraw(const calibration::CalibrationSet& set, DeviceSpec& spec, const calibration::DeviceCalibration* cal);
std::string hidraw_calibration(const calibration::CalibrationSet& set, const DeviceSpec& spec,
                               const calibration::DeviceCalibration* cal);

// Force-feedback input event devices, the kernel's driver doing the force feedback: `evdev` or `evdev:PATH`.
bool is_evdev_device(const std::string& device);
bool serves_evdev(const DeviceSpec& spec, const calibration::DeviceCalibration* cal);
OpenedDevice open_evdev(const calibration::CalibrationSet& set, DeviceSpec& spec, const calibration::DeviceCalibration* cal);
std::string evdev_calibration(const calibration::CalibrationSet& set, const DeviceSpec& spec,
                              const calibration::DeviceCalibration* cal);

}  // namespace sandpaper::runtime
