#pragma once
// One factory for every device Sandpaper plays on: the simulated joystick (moved by a scripted hand,
// the dynamic hand, a replayed trace or the studio's pointer), a historical device emulated on it
// (a calibration file with [emulation]: sandpaper-1995, Minsky 1995 Table 2), and USB HID PID
// joysticks (a calibration file with [usb]; docs/USB_PID.md). Which family opens a device is decided
// here, from its device calibration, and nowhere else; docs/ARCHITECTURE.md says how to add one.
#include <cstddef>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/runtime/device.hpp"
#include "sandpaper/runtime/device_limits.hpp"
#include "sandpaper/runtime/dynamic_hand.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/emulated_joystick.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/runtime/usb/libusb_transport.hpp"

namespace sandpaper::runtime {

class DummyJoystick;
class RecordingDevice;
namespace usb {
class HidPidJoystick;
}

// What moves a simulated handle. A real device is moved by a person's hand: it ignores Script and
// Pointer, and refuses Dynamic and Replay, which were asked for on purpose.
enum class SimulatedHand {
  Script,   // the handle follows `DeviceSpec::script` exactly (position-controlled)
  Dynamic,  // a mass pulled along the script by the hand's spring and damper (`DeviceSpec::hand_model`)
  Replay,   // the positions of a recorded trace, one per tick (`DeviceSpec::replay_positions_m`)
  Pointer,  // the studio's Dummy mode: the handle moves toward a target the page sets (DummyJoystick)
};

// Units: SI.
struct DeviceSpec {
  // A device calibration's name ("sim", "sandpaper-1995", "openffboard-2axis"); "usb": the first
  // USB joystick plugged in whose calibration is known, through libusb (usbhid detached while it plays);
  // "hidraw" or "hidraw:PATH": the first such joystick's hidraw node, or that node, the kernel's driver left bound;
  // "evdev" or "evdev:PATH": the first force-feedback input event node a calibration names, or that node.
  std::string device = "sim";
  // Play the named calibration's device on the simulated joystick (its limits), not through its driver.
  bool simulate = false;
  SimulatedHand hand = SimulatedHand::Script;
  HandScript script;
  HandModel hand_model;
  std::vector<glm::dvec2> replay_positions_m;  // Replay; moved from by open_device
  std::string replay_name;                     // Replay: where the positions came from, for the description
  double pointer_speed_m_s = 0.2;              // Pointer: the handle's top speed toward the target
  std::size_t record_ticks = 0;                // ticks a simulated device keeps for records()
  double watchdog_s = 0;    // a real device: no position, or no force taken, this long stops the loop (0: its file's)
  bool virtual_clock = false;  // the run will be on simulated time: only simulated devices can follow it
  // How a calibrated joystick named by `device` is reached: "" (libusb), "hidraw[:PATH]" or "evdev[:PATH]".
  // Set when `device` was "hidraw..." or "evdev..." and has been resolved to the calibration it found.
  std::string through;
  // An evdev device no calibration file names may play, with the uncalibrated-evdev profile
  // (calibration/profiles/): its assumed scale and a quarter of the level range. Evdev only.
  bool uncalibrated = false;
};

struct OpenedDevice {
  std::unique_ptr<Device> device;
  const char* family = "";            // "simulated", "emulated", "usb", "hidraw" or "evdev": the factory entry that opened it
  std::string calibration;            // the device calibration programs must be compiled for
  std::string description;            // "position-controlled hand", "openffboard-2axis (1209:ffb0) on USB bus 1 address 3"
  RecordingDevice* recording = nullptr;  // simulated and emulated devices: their tick records
  DummyJoystick* pointer = nullptr;      // SimulatedHand::Pointer: where the page moves the handle
  std::optional<Emulation> emulation;    // an emulated device's quantisation
  std::optional<usb::UsbHidDeviceInfo> usb;  // a USB device: where it is
  std::string node;                   // a device played through hidraw: its node ("/dev/hidraw0"); else empty
  usb::HidPidJoystick* usb_joystick = nullptr;  // ... and its driver, for fault_status() after a run
  HeldDevice* held = nullptr;         // a device a person holds: closed (given back) before the run is reported
  std::string transport;              // a held device: "libusb", "hidraw" or "evdev"
  bool real = false;                  // a device a person moves (USB), not a simulated one
  std::string warning;                // non-empty: say it before playing (profile_warning)
};

// Why a device could not be opened. `help` holds lines to print after the message (the udev rule
// that grants access), or is empty.
class DeviceOpenError : public std::runtime_error {
 public:
  enum class Cause {
    UnknownDevice,   // no calibration by that name
    NoDriver,        // a calibration with neither [usb] nor [emulation], asked for its driver
    WrongOptions,    // options the device cannot honour (a replay on a real joystick, a watchdog on a simulated one)
    NoUsb,           // USB cannot be searched, or no force-feedback device is plugged in
    NoCalibration,   // force-feedback devices are present but none has a calibration
    AccessDenied,    // the device is there but this user may not open it
    Refused,         // the device opened but the driver could not start it (HidPidError)
  };
  DeviceOpenError(Cause why, const std::string& message, std::string help_lines = {})
      : std::runtime_error(message), cause(why), help(std::move(help_lines)) {}
  Cause cause;
  std::string help;
};

// Opens the device `spec` names. `set` holds the device calibrations. Throws DeviceOpenError; the
// message starts lower-case so the caller can prefix its command ("sandpaper run: ...").
OpenedDevice open_device(const calibration::CalibrationSet& set, DeviceSpec spec);

// What open_device(set, spec) would open, found without opening anything: the device calibration
// (`spec.device` itself, or for "usb" the calibration of the first known joystick plugged in), so
// programs are compiled for it before the device is claimed. Throws DeviceOpenError as open_device does.
struct DeviceChoice {
  std::string calibration;
  const char* family = "";
  bool real = false;     // a device a person moves (USB), not a simulated one
  std::string warning;   // non-empty: say it before playing (profile_warning)
};
DeviceChoice choose_device(const calibration::CalibrationSet& set, const DeviceSpec& spec);

// When `calibration` is one of `set`'s profiles (a device no calibration file names, played with
// --uncalibrated), one sentence for every caller to show before it plays: the profile's scale,
// travel and directions are assumptions, where its forces stop, and how to calibrate the device
// (docs/DEVICES.md). Empty for a device's own file.
std::string profile_warning(const calibration::CalibrationSet& set, const std::string& calibration);

// What `run` plays on when no device is named: the hidraw node of a calibrated HID PID joystick
// plugged in ("hidraw:/dev/hidraw0"), else its input event node ("evdev:/dev/input/event3"),
// preferring a node this user may open; else the event node of any force-feedback device this user
// may open (which then plays only with --uncalibrated); else "sim". `found` describes the joystick ("" for sim).
// Opens nothing; never throws. libusb is only ever taken when asked for (--device usb).
struct DefaultDevice {
  std::string device;
  std::string found;
};
DefaultDevice default_play_device(const calibration::CalibrationSet& set);

// The quantisation and table sampling of a calibration with [emulation]; nullopt for others.
std::optional<Emulation> emulation_of(const calibration::DeviceCalibration& device);

// USB HID devices that are force-feedback joysticks: a PID usage in the report descriptor, or a
// VID:PID a device calibration names (then `calibration` is that calibration, else nullptr).
struct UsbCandidate {
  usb::UsbHidDeviceInfo info;
  const calibration::DeviceCalibration* calibration = nullptr;
};
struct UsbSearch {
  bool searched = false;        // false: USB could not be searched (`message` says why)
  std::string message;
  std::size_t hid_devices = 0;  // USB HID devices checked
  std::vector<UsbCandidate> found;
};
UsbSearch find_usb_devices(const calibration::CalibrationSet& set);

// "1209:ffb0"
std::string usb_ids(int vendor, int product);
// "openffboard-2axis (1209:ffb0)", comma-separated, or "none": the USB devices `set` knows.
std::string known_usb_devices(const calibration::CalibrationSet& set);
// The udev rule line that gives the logged-in user the device (through libusb).
std::string udev_rule(int vendor, int product);
// The udev rule line that gives the logged-in user the device's hidraw nodes.
std::string hidraw_udev_rule(int vendor, int product);
// The rules file for /usr/lib/udev/rules.d/70-sandpaper.rules: uaccess for the hidraw nodes of the
// USB devices `set` names and for input event devices with force feedback (lines of udev syntax).
std::string udev_rules_file(const calibration::CalibrationSet& set);
// What to do about a device this user may not open: the rule, where it goes, how to load it (lines).
std::string udev_help(int vendor, int product);
// Why none was found, when this system has no USB bus at all (a container or a VM without passthrough); else "".
std::string no_usb_bus_note();

}  // namespace sandpaper::runtime
