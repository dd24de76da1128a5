#include "sandpaper/runtime/devices/open_device.hpp"

#include <algorithm>
#include <cstdio>

#include "devices_internal.hpp"
#include "sandpaper/runtime/devices/usb_port.hpp"
#include "sandpaper/runtime/dummy_joystick.hpp"
#include "sandpaper/runtime/replay_joystick.hpp"

namespace sandpaper::runtime {
namespace {

using Cause = DeviceOpenError::Cause;
using calibration::DeviceCalibration;

// The simulated handle and what moves it.
std::unique_ptr<RecordingDevice> simulated_handle(DeviceSpec& spec, const DeviceLimits& limits, std::size_t record_ticks) {
  switch (spec.hand) {
    case SimulatedHand::Replay:
      return std::make_unique<ReplayJoystick>(limits, std::move(spec.replay_positions_m));
    case SimulatedHand::Dynamic:
      return std::make_unique<DynamicHandJoystick>(limits, spec.script, spec.hand_model, record_ticks);
    case SimulatedHand::Script:
    case SimulatedHand::Pointer:
      break;
  }
  return std::make_unique<SimJoystick>(limits, spec.script, record_ticks);
}

std::string describe_hand(const DeviceSpec& spec) {
  switch (spec.hand) {
    case SimulatedHand::Replay:
      return "replay of " + (spec.replay_name.empty() ? std::string("a recorded trace") : spec.replay_name);
    case SimulatedHand::Dynamic:
      return "dynamic hand (" + g_text(spec.hand_model.mass_kg) + " kg, " + g_text(spec.hand_model.stiffness_N_per_m) +
             " N/m, " + g_text(spec.hand_model.damping_Ns_per_m) + " N*s/m)";
    case SimulatedHand::Pointer:
      return "Dummy mode: the handle follows the pointer";
    case SimulatedHand::Script:
      break;
  }
  return "position-controlled hand";
}

void refuse_watchdog(const DeviceSpec& spec) {
  if (spec.watchdog_s != 0)
    throw DeviceOpenError(Cause::WrongOptions, "--watchdog applies to --device usb (a simulated joystick cannot go quiet)");
}

// A device simulated with a calibration's limits: `sim`, or any device asked for with `simulate`.
bool serves_simulated(const DeviceSpec& spec, const DeviceCalibration* cal) {
  return cal != nullptr && !cal->emulated && (cal->name == "sim" || spec.simulate);
}
std::string simulated_calibration(const calibration::CalibrationSet&, const DeviceSpec& spec, const DeviceCalibration* cal) {
  refuse_watchdog(spec);
  return cal->name;
}

OpenedDevice open_simulated(const calibration::CalibrationSet& set, DeviceSpec& spec, const DeviceCalibration* cal) {
  OpenedDevice out;
  out.calibration = simulated_calibration(set, spec, cal);
  out.description = describe_hand(spec);
  const DeviceLimits limits = limits_of(*cal);
  if (spec.hand == SimulatedHand::Pointer) {
    auto pointer = std::make_unique<DummyJoystick>(limits, spec.pointer_speed_m_s);
    out.pointer = pointer.get();
    out.device = std::move(pointer);
    return out;
  }
  auto device = simulated_handle(spec, limits, spec.record_ticks);
  out.recording = device.get();
  out.device = std::move(device);
  return out;
}

// A historical device ([emulation]): the simulated handle, read and driven through its quantisation.
bool serves_emulated(const DeviceSpec&, const DeviceCalibration* cal) { return cal != nullptr && cal->emulated; }
std::string emulated_calibration(const calibration::CalibrationSet&, const DeviceSpec& spec, const DeviceCalibration* cal) {
  refuse_watchdog(spec);
  if (spec.hand == SimulatedHand::Pointer)
    throw DeviceOpenError(Cause::WrongOptions, "device '" + cal->name +
                                                   "' is emulated on the simulated joystick; the studio's Dummy mode plays --device sim");
  return cal->name;
}

OpenedDevice open_emulated(const calibration::CalibrationSet& set, DeviceSpec& spec, const DeviceCalibration* cal) {
  OpenedDevice out;
  out.calibration = emulated_calibration(set, spec, cal);
  out.description = describe_hand(spec);
  out.emulation = emulation_of(*cal);
  // The inner handle's own records are not used: the quantising device records what the tick saw.
  auto device = std::make_unique<EmulatedJoystick>(simulated_handle(spec, limits_of(*cal), 0),
                                                     *out.emulation, spec.record_ticks);
  out.recording = device.get();
  out.device = std::move(device);
  return out;
}

struct Family {
  const char* name;
  bool real;
  bool (*serves)(const DeviceSpec&, const DeviceCalibration*);
  OpenedDevice (*open)(const calibration::CalibrationSet&, DeviceSpec&, const DeviceCalibration*);
  std::string (*calibration)(const calibration::CalibrationSet&, const DeviceSpec&, const DeviceCalibration*);
};

// The device families, asked in order; the first that serves a spec opens it. A new driver is one
// entry here (and its open function).
constexpr Family kFamilies[] = {
    {"emulated", false, serves_emulated, open_emulated, emulated_calibration},
    {"simulated", false, serves_simulated, open_simulated, simulated_calibration},
    {"hidraw", true, serves_hidraw, open_hidraw, hidraw_calibration},
    {"evdev", true, serves_evdev, open_evdev, evdev_calibration},
    {"usb", true, serves_usb, open_usb, usb_calibration},
};

bool is_profile(const calibration::CalibrationSet& set, const DeviceCalibration* cal) {
  for (const auto& p : set.profiles())
    if (&p == cal) return true;
  return false;
}

const Family& family_for(const calibration::CalibrationSet& set, const DeviceSpec& spec, const DeviceCalibration*& cal) {
  const bool searched = spec.device == "usb" || is_hidraw_device(spec.device) || is_evdev_device(spec.device);  // found on the bus, not named
  cal = searched ? nullptr : set.find_device(spec.device);
  if (!searched && cal == nullptr) {
    std::string names;
    for (const auto& d : set.devices()) names += (names.empty() ? "" : ", ") + d.name;
    throw DeviceOpenError(Cause::UnknownDevice, "no device calibration named '" + spec.device + "' (devices: " + names + ", or usb, hidraw, hidraw:PATH, evdev, evdev:PATH)");
  }
  if (is_profile(set, cal) && !is_evdev_device(spec.through))
    throw DeviceOpenError(Cause::WrongOptions, "'" + spec.device + "' is a profile for devices without a calibration file, not a device: play "
                                               "such a device with --device evdev (or evdev:PATH) --uncalibrated");
  if (spec.uncalibrated && !is_evdev_device(spec.device) && !is_evdev_device(spec.through))
    throw DeviceOpenError(Cause::WrongOptions, "--uncalibrated plays an input event node that no calibration file names: "
                                               "give it with --device evdev or evdev:PATH");
  for (const Family& family : kFamilies)
    if (family.serves(spec, cal)) return family;
  throw DeviceOpenError(Cause::NoDriver, "device '" + spec.device +
                                             "' cannot be played: its calibration has neither a [usb] table (a USB HID PID "
                                             "joystick) nor [emulation]; play on --device sim, an emulated device, or usb");
}

}  // namespace

std::string g_text(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%g", v);
  return s;
}

OpenedDevice open_device(const calibration::CalibrationSet& set, DeviceSpec spec) {
  const DeviceCalibration* cal = nullptr;
  const Family& family = family_for(set, spec, cal);
  OpenedDevice out = family.open(set, spec, cal);
  out.family = family.name;
  out.real = family.real;
  out.warning = profile_warning(set, out.calibration);
  // Where a held USB device sits, read now, before it can go: a run that loses it and finds it back
  // at the same port under a new address names a reset (LiveServo::join_nonrt), whoever plays it.
  if (out.held != nullptr) {
    std::optional<UsbPort> port;
    if (!out.node.empty()) port = usb_port_of_node(out.node);
    else if (out.usb) port = usb_port_of_address(out.usb->bus, out.usb->address);
    if (port) out.held->watch_for_return_nonrt([at = *port](double within_s) { return came_back_nonrt(at, within_s); });
  }
  return out;
}

DeviceChoice choose_device(const calibration::CalibrationSet& set, const DeviceSpec& spec) {
  const DeviceCalibration* cal = nullptr;
  const Family& family = family_for(set, spec, cal);
  DeviceChoice choice{family.calibration(set, spec, cal), family.name, family.real, {}};
  choice.warning = profile_warning(set, choice.calibration);
  return choice;
}

std::string profile_warning(const calibration::CalibrationSet& set, const std::string& calibration) {
  const auto& profiles = set.profiles();
  const auto p = std::find_if(profiles.begin(), profiles.end(), [&](const DeviceCalibration& d) { return d.name == calibration; });
  if (p == profiles.end()) return {};
  return "no calibration file names this device: playing it with the profile " + p->file +
         ", whose scale, travel and directions are assumptions; forces stop at " + g_text(p->max_force_N) +
         " N as it reckons them (" + std::to_string(p->command_max) + " " + p->command_unit +
         " at most); measure the device with `sandpaper calibrate device` (docs/CALIBRATION.md)";
}

std::optional<Emulation> emulation_of(const DeviceCalibration& device) {
  if (!device.emulated) return std::nullopt;
  Emulation e;
  e.quantization.position_step_m = device.position_resolution_m;
  for (int a = 0; a < 2; ++a) e.quantization.force_step_N[a] = device.quantized() ? device.force_step_N(a) : 0.0;
  e.quantization.command_max = device.command_max;
  e.tables = device.hold_tables ? TableSampling::Hold : TableSampling::Interpolate;
  return e;
}

}  // namespace sandpaper::runtime
