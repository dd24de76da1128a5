#pragma once
// Playing one patch program, the part of `sandpaper run` that needs no compiler: shared by
// `sandpaper run` (which compiles first) and the runtime-only `sandpaper-play` (which reads a
// compiled .patch). Prints the run's report (text or --json) and returns the exit code.
#include <functional>
#include <string>

namespace CLI {
class App;  // not <CLI/CLI.hpp>: that header-only library costs every includer seconds to compile
}

#include "sandpaper/player/run_device.hpp"
#include "sandpaper/player/safety_guards.hpp"
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/runtime/devices/open_device.hpp"
#include "sandpaper/runtime/force_source.hpp"
#include "sandpaper/player/play.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/emulated_joystick.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::cli {

// Units at the boundary: Hz, s, mm/s, mm, us, periods.
struct PlayRequest {
  double rate_hz = 1000, duration_s = 2, speed_mm_s = 50, amplitude_mm = 30, hand_start_mm = 0;
  std::string hand = "scan", trace;
  bool virtual_clock = false, live = false, json = false;
  RunDeviceOptions device;
  double spin_margin_us = runtime::ServoConfig{}.spin_margin_s * 1e6;
  SafetyGuards guards;
  int cpu = -1;
  bool rate_given = false;  // --rate was on the command line
  // A device emulated on the simulator ([emulation] in its device file; apply_emulation sets these).
  bool emulated = false;
  runtime::DeviceQuantization quantization;
  runtime::TableSampling tables = runtime::TableSampling::Interpolate;
};

// For a device whose file has [emulation] (sandpaper-1995): plays on the simulated joystick with the
// device's position and force quantisation and table sampling, at its servo rate unless --rate was
// given (1000 Hz clamped to the device's range). Does nothing for other devices.
void apply_emulation(const calibration::DeviceCalibration& device, PlayRequest& r);

// Registers run's playing options on `run` (--rate ... --trace, --virtual-clock, --live, the hand
// device options, --spin-margin, --deadline-guard, --cpu). The same for `sandpaper run` and `sandpaper-play`.
void add_play_options(CLI::App* run, PlayRequest& r);

// Which executable is playing: "sandpaper-play" (the runtime alone) or "sandpaper" (compiled in-process).
std::string player_name();

// The servo settings of a request.
runtime::ServoConfig servo_config_of(const PlayRequest& r);

// 0 when `trace` is empty or its folder is writable; else kExitUsage after saying so.
int check_trace_folder(const std::string& trace);

// Checks what can be checked before loading the material (rate and servo settings for the device,
// hand speed and amplitude, a writable trace folder): 0, or kExitUsage after printing why.
int check_play_request(const PlayRequest& r, const runtime::DeviceLimits& limits);
// --duration (s) within schema::limits::kMaxRunSeconds, and a run that keeps a record of every tick
// within kMaxRecordedTicks at `rate_hz`; kExitOk, or kExitUsage after saying why.
int check_run_length(double duration_s, double rate_hz, bool records_every_tick);

// The device spec (runtime/devices/open_device.hpp) of a request to play on `device` (a calibration's
// name, or usb): the hand options, the replayed positions, the ticks to record.
runtime::DeviceSpec device_spec_of(const PlayRequest& r, const std::string& device);

// Everything about playing `r` on `device` (a calibration's name, or usb) that can be settled before
// the material is compiled and the device claimed: which calibration the device takes programs for
// (for usb, the joystick plugged in: found, not opened), an emulated device's settings applied to `r`,
// --replay loaded (setting the duration), the request checked against the device's limits. Fills
// `spec` for open_play_device; `spec.device` is then the calibration to compile for, and `*real`
// (when given) whether a person's hand moves the device. kExitOk, or kExitUsage / kExitBadInput after
// printing why, naming `command` ("run --device usb").
int prepare_play_device(const calibration::CalibrationSet& set, const std::string& device, PlayRequest& r,
                        runtime::DeviceSpec& spec, const std::string& command, bool* real = nullptr);
// Opens the device prepare_play_device settled on: kExitOk, or kExitUsage after printing why.
int open_play_device(const calibration::CalibrationSet& set, runtime::DeviceSpec spec, runtime::OpenedDevice& out,
                     const std::string& command);

// Plays `program` on `device` (from open_play_device; the program must be compiled for its
// calibration) and reports. `roughness_map` predicts the felt roughness from the measured force.
// `swaps`: run --watch's reloads, offered to the run's host while it plays (play.hpp).
int play_patch(const schema::PatchProgram& program, runtime::OpenedDevice& device,
               const calibration::PsychophysicalMap& roughness_map, const PlayRequest& r, const Swaps& swaps = {});

}  // namespace sandpaper::cli
