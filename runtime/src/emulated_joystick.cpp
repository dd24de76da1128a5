#include "sandpaper/runtime/emulated_joystick.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace sandpaper::runtime {

glm::dvec2 quantize_position(glm::dvec2 p, double step_m) noexcept {
  if (!(step_m > 0)) return p;
  return {std::round(p.x / step_m) * step_m, std::round(p.y / step_m) * step_m};
}

glm::dvec2 quantize_force(glm::dvec2 f, const DeviceQuantization& q) noexcept {
  glm::dvec2 out = f;
  for (int a = 0; a < 2; ++a) {
    const double step = q.force_step_N[a];
    if (!(step > 0)) continue;
    double units = std::round(f[a] / step);  // NaN stays NaN: the loop stops on it
    if (q.command_max > 0) units = std::clamp(units, -static_cast<double>(q.command_max), static_cast<double>(q.command_max));
    out[a] = units * step;
  }
  return out;
}

EmulatedJoystick::EmulatedJoystick(std::unique_ptr<RecordingDevice> inner, Emulation emulation, std::size_t capacity_ticks)
    : RecordingDevice(capacity_ticks), inner_(std::move(inner)), emulation_(emulation) {}

CommandQuantum EmulatedJoystick::command_quantum() const noexcept {
  CommandQuantum c;
  c.step_N[0] = emulation_.quantization.force_step_N[0];
  c.step_N[1] = emulation_.quantization.force_step_N[1];
  c.max_steps = emulation_.quantization.command_max;
  return c;
}

bool EmulatedJoystick::read_position_rt(double t_s, glm::dvec2& position_m) noexcept {
  glm::dvec2 p{0, 0};
  if (!inner_->read_position_rt(t_s, p)) return false;
  position_m = quantize_position(p, emulation_.quantization.position_step_m);
  note_read_rt(t_s, position_m);
  return true;
}

bool EmulatedJoystick::write_force_rt(glm::dvec2 force_N) noexcept {
  const glm::dvec2 sent = quantize_force(force_N, emulation_.quantization);
  note_write_rt(sent);
  return inner_->write_force_rt(sent);
}

}  // namespace sandpaper::runtime
