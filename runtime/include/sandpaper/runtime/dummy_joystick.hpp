#pragma once
// The thesis' Dummy mode (Minsky 1995, Appendix B: the mouse moves the cursor when no joystick is
// attached), as a simulated device: another thread sets where the hand should be (the studio's mouse
// over the preview); each tick the handle moves toward that point at no more than a hand's speed, so
// a jump of the mouse becomes a stroke the servo loop can filter, not a velocity spike that trips
// its velocity limit. The last position and force written are readable from any thread.
#include <atomic>

#include "sandpaper/runtime/device.hpp"

namespace sandpaper::runtime {

class DummyJoystick final : public Device {
 public:
  // `max_speed_m_s` (> 0, finite): the handle's top speed toward the target, m/s. The default, 0.2 m/s,
  // is a brisk stroke (a design choice, not a measurement), a tenth of the servo loop's 2 m/s limit.
  explicit DummyJoystick(DeviceLimits limits, double max_speed_m_s = 0.2);
  const DeviceLimits& limits() const noexcept override { return limits_; }
  bool read_position_rt(double t_s, glm::dvec2& position_m) noexcept override;
  bool write_force_rt(glm::dvec2 force_N) noexcept override;

  // Any thread. The point (m, patch or workspace coordinates) the hand moves toward; clipped to the
  // workspace radius. Non-finite coordinates are ignored. Returns the target the hand now moves to.
  glm::dvec2 set_target_nonrt(glm::dvec2 target_m) noexcept;
  glm::dvec2 target_nonrt() const noexcept;
  // Any thread: the handle's position (m) at the last tick and the last force written (N).
  glm::dvec2 position_nonrt() const noexcept;
  glm::dvec2 force_nonrt() const noexcept;

 private:
  DeviceLimits limits_;
  double max_speed_m_s_;
  // x and y are separate atomics: a reader may see x of one update and y of the next, which for a
  // display or a target a hand is dragging toward is harmless, and keeps every access lock-free.
  std::atomic<double> target_x_{0}, target_y_{0};
  std::atomic<double> pos_x_{0}, pos_y_{0};
  std::atomic<double> force_x_{0}, force_y_{0};
  // Servo thread's own.
  glm::dvec2 position_{0, 0};
  double last_t_s_ = 0;
  bool started_ = false;
};

}  // namespace sandpaper::runtime
