#pragma once
// A historical device emulated on a simulated one, owning every setting of the emulation: positions
// read in encoder steps, forces sent in whole command units and clamped at the largest command, and
// force tables read sample-and-hold, as the thesis' joystick did (Minsky 1995, Table 2: 12-bit
// positions across the 9 inch workspace, 12-bit force commands; Table 6: 1 joystick unit =
// 0.490909 gf; Appendix B 2.1: tables held between samples). It describes its commands and its table
// sampling (Device::command_quantum, Device::table_sampling), so the servo loop rounds its commands
// to the same steps (its telemetry shows the staircase sent) and every host builds its force sources
// with the same sampling, on the steady and the virtual clock alike. Rounding here again changes
// nothing then, and keeps the device honest when driven by anything else.
#include <cstddef>
#include <memory>

#include "sandpaper/runtime/recording_device.hpp"

namespace sandpaper::runtime {

// SI units; 0 leaves that quantity continuous.
struct DeviceQuantization {
  double position_step_m = 0;          // one encoder count (sandpaper-1995: 228.6 mm / 4096 = 0.0558 mm)
  double force_step_N[2] = {0, 0};     // newtons per command unit, x and y (sandpaper-1995: 4.814 mN)
  long command_max = 0;                // largest command magnitude per axis (sandpaper-1995: 2048)
};

// A historical device's quantisation and table sampling ([emulation] in its calibration file).
struct Emulation {
  DeviceQuantization quantization;
  TableSampling tables = TableSampling::Interpolate;
};

// Position `p` (m) on the nearest encoder count; unchanged when `step_m` is 0. Pure.
glm::dvec2 quantize_position(glm::dvec2 p, double step_m) noexcept;
// Force `f` (N) in whole command units per axis, clamped at +-command_max units. Pure.
glm::dvec2 quantize_force(glm::dvec2 f, const DeviceQuantization& q) noexcept;

class EmulatedJoystick final : public RecordingDevice {
 public:
  // `inner` moves the handle (the scripted or dynamic hand); its own records are not used, so give it
  // a capacity of 0. `capacity_ticks`: how many quantised ticks this device records.
  EmulatedJoystick(std::unique_ptr<RecordingDevice> inner, Emulation emulation, std::size_t capacity_ticks);
  const DeviceLimits& limits() const noexcept override { return inner_->limits(); }
  CommandQuantum command_quantum() const noexcept override;
  TableSampling table_sampling() const noexcept override { return emulation_.tables; }
  bool follows_virtual_clock() const noexcept override { return inner_->follows_virtual_clock(); }
  bool read_position_rt(double t_s, glm::dvec2& position_m) noexcept override;
  bool write_force_rt(glm::dvec2 force_N) noexcept override;
  DeviceFault last_fault_rt() const noexcept override { return inner_->last_fault_rt(); }
  const Emulation& emulation() const noexcept { return emulation_; }

 private:
  std::unique_ptr<RecordingDevice> inner_;
  Emulation emulation_;
};

}  // namespace sandpaper::runtime
