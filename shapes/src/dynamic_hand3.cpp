#include "sandpaper/shapes/dynamic_hand3.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>

namespace sandpaper::shapes {

DynamicHand3::DynamicHand3(DeviceLimits3 limits, HandPath3 path, runtime::HandModel model, std::size_t capacity_ticks)
    : limits_(std::move(limits)), path_(std::move(path)), model_(model), capacity_(capacity_ticks) {
  if (!std::isfinite(model.mass_kg) || model.mass_kg <= 0)
    throw std::invalid_argument("hand model: the handle's mass must be a positive, finite number of kg");
  if (!std::isfinite(model.stiffness_N_per_m) || model.stiffness_N_per_m < 0)
    throw std::invalid_argument("hand model: the hand's stiffness must be a finite number of N/m, 0 or more");
  if (!std::isfinite(model.damping_Ns_per_m) || model.damping_Ns_per_m < 0)
    throw std::invalid_argument("hand model: the hand's damping must be a finite number of N*s/m, 0 or more");
  if (!std::isfinite(model.max_substep_s) || model.max_substep_s <= 0)
    throw std::invalid_argument("hand model: the integration substep must be a positive, finite time");
  records_.reserve(capacity_ticks);
}

double DynamicHand3::energy_J() const noexcept {
  const glm::dvec3 dv = v_ - path_.velocity(t_);
  const glm::dvec3 dx = x_ - path_.position(t_);
  return 0.5 * model_.mass_kg * glm::dot(dv, dv) + 0.5 * model_.stiffness_N_per_m * glm::dot(dx, dx);
}

bool DynamicHand3::read_position_rt(double t_s, glm::dvec3& position_m) noexcept {
  if (!started_) {
    started_ = true;
    t_ = t_s;
    x_ = path_.position(t_s);
    v_ = path_.velocity(t_s);
  } else if (t_s > t_) {
    // Semi-implicit (symplectic) Euler in equal substeps: velocity first under the forces at the
    // substep's end-of-step hand point, then position with the new velocity (runtime's
    // DynamicHandJoystick, docs/RUNTIME.md: stable for h sqrt(k/m) < 2 and h b/m < 2). The held
    // force's work is F . dx summed over the substeps, exact for a constant F; the damper's
    // dissipation b |p' - v|^2 h at the substep's new velocity.
    const double span = t_s - t_;
    const auto n = static_cast<long>(std::ceil(span / model_.max_substep_s));
    const double h = span / static_cast<double>(n);
    const double inv_m = 1.0 / model_.mass_kg;
    for (long i = 1; i <= n; ++i) {
      const double ti = t_ + h * static_cast<double>(i);
      const glm::dvec3 hand = path_.position(ti);
      const glm::dvec3 hand_v = path_.velocity(ti);
      const glm::dvec3 f = model_.stiffness_N_per_m * (hand - x_) + model_.damping_Ns_per_m * (hand_v - v_) + force_;
      v_ += h * inv_m * f;
      const glm::dvec3 dx = h * v_;
      x_ += dx;
      work_J_ += glm::dot(force_, dx);
      const glm::dvec3 slip = hand_v - v_;
      dissipated_J_ += model_.damping_Ns_per_m * glm::dot(slip, slip) * h;
    }
    t_ = t_s;
  }
  read_since_write_ = true;
  position_m = x_;
  return std::isfinite(x_.x) && std::isfinite(x_.y) && std::isfinite(x_.z);
}

bool DynamicHand3::write_force_rt(const glm::dvec3& force_N) noexcept {
  force_ = force_N;
  if (read_since_write_ && records_.size() < capacity_)
    records_.push_back(HandTick3{t_, path_.position(t_), path_.velocity(t_), x_, v_, force_N, energy_J(), dissipated_J_, work_J_});
  read_since_write_ = false;
  return true;
}

DynamicHand3 open_sim3d(HandPath3 path, std::size_t capacity_ticks, runtime::HandModel model) {
  return DynamicHand3(sim3d_limits(), std::move(path), model, capacity_ticks);
}

}  // namespace sandpaper::shapes
