#include "sandpaper/runtime/dynamic_hand.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace sandpaper::runtime {
namespace {

// Central difference over 1 us: exact on the straight and circular pieces of the scripted paths,
// a blend of the two speeds within 1 us of a scan's turn.
constexpr double kPathDiff_s = 1e-6;

}  // namespace

DynamicHandJoystick::DynamicHandJoystick(DeviceLimits limits, HandScript script, HandModel model,
                                         std::size_t capacity_ticks)
    : RecordingDevice(capacity_ticks), limits_(std::move(limits)), script_(script), model_(model), capacity_(capacity_ticks) {
  if (!std::isfinite(model.mass_kg) || model.mass_kg <= 0)
    throw std::invalid_argument("hand model: the handle's mass must be a positive, finite number of kg");
  if (!std::isfinite(model.stiffness_N_per_m) || model.stiffness_N_per_m < 0)
    throw std::invalid_argument("hand model: the hand's stiffness must be a finite number of N/m, 0 or more");
  if (!std::isfinite(model.damping_Ns_per_m) || model.damping_Ns_per_m < 0)
    throw std::invalid_argument("hand model: the hand's damping must be a finite number of N*s/m, 0 or more");
  if (!std::isfinite(model.max_substep_s) || model.max_substep_s <= 0)
    throw std::invalid_argument("hand model: the integration substep must be a positive, finite time");
  hand_records_.reserve(capacity_ticks);
}

glm::dvec2 DynamicHandJoystick::path_velocity(double t_s) const noexcept {
  const double a = t_s > kPathDiff_s ? t_s - kPathDiff_s : 0.0;
  const double b = t_s + kPathDiff_s;
  return (scripted_hand_position(script_, b) - scripted_hand_position(script_, a)) / (b - a);
}

double DynamicHandJoystick::energy_J(double t_s) const noexcept {
  const glm::dvec2 dv = v_ - path_velocity(t_s);
  const glm::dvec2 dx = x_ - scripted_hand_position(script_, t_s);
  return 0.5 * model_.mass_kg * (dv.x * dv.x + dv.y * dv.y) + 0.5 * model_.stiffness_N_per_m * (dx.x * dx.x + dx.y * dx.y);
}

bool DynamicHandJoystick::read_position_rt(double t_s, glm::dvec2& position_m) noexcept {
  if (!started_) {
    started_ = true;
    t_ = t_s;
    x_ = scripted_hand_position(script_, t_s);
    v_ = path_velocity(t_s);
  } else if (t_s > t_) {
    // Semi-implicit (symplectic) Euler in equal substeps of at most max_substep_s: velocity first
    // under the forces at the substep's end-of-step hand point, then position with the new velocity.
    // Stable for h sqrt(k/m) < 2 and h b/m < 2; the defaults keep both under 0.002.
    const double span = t_s - t_;
    const auto n = static_cast<long>(std::ceil(span / model_.max_substep_s));
    const double h = span / static_cast<double>(n);
    const double inv_m = 1.0 / model_.mass_kg;
    for (long i = 1; i <= n; ++i) {
      const double ti = t_ + h * static_cast<double>(i);
      const glm::dvec2 hand = scripted_hand_position(script_, ti);
      const glm::dvec2 hand_v = path_velocity(ti);
      const glm::dvec2 f = model_.stiffness_N_per_m * (hand - x_) + model_.damping_Ns_per_m * (hand_v - v_) + force_;
      v_ += h * inv_m * f;
      x_ += h * v_;
    }
    t_ = t_s;
  }
  position_m = x_;
  note_read_rt(t_s, x_);
  return std::isfinite(x_.x) && std::isfinite(x_.y);
}

bool DynamicHandJoystick::write_force_rt(glm::dvec2 force_N) noexcept {
  force_ = force_N;
  if (note_write_rt(force_N) && hand_records_.size() < capacity_)
    hand_records_.push_back(HandTickRecord{t_, scripted_hand_position(script_, t_), path_velocity(t_), x_, v_, energy_J(t_)});
  return true;
}

}  // namespace sandpaper::runtime
