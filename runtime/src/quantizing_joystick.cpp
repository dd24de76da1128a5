#include "sandpaper/runtime/quantizing_joystick.hpp"

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

QuantizingJoystick::QuantizingJoystick(std::unique_ptr<RecordingDevice> inner, DeviceQuantization q, std::size_t capacity_ticks)
    : RecordingDevice(capacity_ticks), inner_(std::move(inner)), q_(q) {}

bool QuantizingJoystick::read_position_rt(double t_s, glm::dvec2& position_m) noexcept {
  glm::dvec2 p{0, 0};
  if (!inner_->read_position_rt(t_s, p)) return false;
  position_m = quantize_position(p, q_.position_step_m);
  note_read_rt(t_s, position_m);
  return true;
}

bool QuantizingJoystick::write_force_rt(glm::dvec2 force_N) noexcept {
  const glm::dvec2 sent = quantize_force(force_N, q_);
  note_write_rt(sent);
  return inner_->write_force_rt(sent);
}

}  // namespace sandpaper::runtime
