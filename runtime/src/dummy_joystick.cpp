#include "sandpaper/runtime/dummy_joystick.hpp"

#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace sandpaper::runtime {

static_assert(std::atomic<double>::is_always_lock_free, "the servo tick may only touch lock-free atomics");

DummyJoystick::DummyJoystick(DeviceLimits limits, double max_speed_m_s)
    : limits_(std::move(limits)), max_speed_m_s_(max_speed_m_s) {
  if (!(max_speed_m_s > 0) || !std::isfinite(max_speed_m_s))
    throw std::invalid_argument("the dummy hand's top speed must be positive and finite (m/s)");
}

bool DummyJoystick::read_position_rt(double t_s, glm::dvec2& position_m) noexcept {
  const glm::dvec2 target{target_x_.load(std::memory_order_relaxed), target_y_.load(std::memory_order_relaxed)};
  const double dt = started_ ? t_s - last_t_s_ : 0.0;
  started_ = true;
  last_t_s_ = t_s;
  const glm::dvec2 to = target - position_;
  const double distance = glm::length(to);
  const double reach = max_speed_m_s_ * std::max(dt, 0.0);
  position_ = distance <= reach ? target : position_ + to * (reach / distance);
  pos_x_.store(position_.x, std::memory_order_relaxed);
  pos_y_.store(position_.y, std::memory_order_relaxed);
  position_m = position_;
  return true;
}

bool DummyJoystick::write_force_rt(glm::dvec2 force_N) noexcept {
  force_x_.store(force_N.x, std::memory_order_relaxed);
  force_y_.store(force_N.y, std::memory_order_relaxed);
  return true;
}

glm::dvec2 DummyJoystick::set_target_nonrt(glm::dvec2 target_m) noexcept {
  if (!std::isfinite(target_m.x) || !std::isfinite(target_m.y)) return target_nonrt();
  // hypot, not glm::length: squaring a target past 1e154 m overflowed to infinity, and the clip then
  // sent the hand to the centre instead of the edge in the target's direction.
  const double r = std::hypot(target_m.x, target_m.y);
  if (r > limits_.workspace_radius_m) target_m *= limits_.workspace_radius_m / r;
  target_x_.store(target_m.x, std::memory_order_relaxed);
  target_y_.store(target_m.y, std::memory_order_relaxed);
  return target_m;
}

glm::dvec2 DummyJoystick::target_nonrt() const noexcept {
  return {target_x_.load(std::memory_order_relaxed), target_y_.load(std::memory_order_relaxed)};
}
glm::dvec2 DummyJoystick::position_nonrt() const noexcept {
  return {pos_x_.load(std::memory_order_relaxed), pos_y_.load(std::memory_order_relaxed)};
}
glm::dvec2 DummyJoystick::force_nonrt() const noexcept {
  return {force_x_.load(std::memory_order_relaxed), force_y_.load(std::memory_order_relaxed)};
}

}  // namespace sandpaper::runtime
