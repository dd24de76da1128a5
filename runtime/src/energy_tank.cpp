#include "sandpaper/runtime/energy_tank.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sandpaper::runtime {

double EnergyTank::pass_rt(double power_W, double dt_s) noexcept {
  // A tank that can never hold energy: the guarded terms are not played at all, even on the first
  // tick (dt = 0) or while they would absorb energy.
  if (budget_J_ <= 0 && refill_W_ <= 0) return 0;
  if (!std::isfinite(power_W)) return std::numeric_limits<double>::quiet_NaN();
  const double dt = dt_s > 0 && std::isfinite(dt_s) ? dt_s : 0.0;

  // This tick's refill and absorption are available to this tick; only what carries over to the
  // next tick is capped at the budget. Capping first would lose a zero-budget tank's refill.
  level_J_ += refill_W_ * dt;
  double scale = 1;
  if (power_W < 0) {
    level_J_ -= power_W * dt;
  } else if (power_W > 0) {
    const double cost_J = power_W * dt;
    if (cost_J <= level_J_) {
      level_J_ -= cost_J;
    } else {
      scale = level_J_ / cost_J;
      level_J_ = 0;
    }
  }
  level_J_ = std::min(level_J_, budget_J_);
  return scale;
}

}  // namespace sandpaper::runtime
