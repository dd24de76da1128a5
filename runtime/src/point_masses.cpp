#include "sandpaper/runtime/point_masses.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sandpaper::runtime {
namespace {

// Stability margins of the step (docs/RUNTIME.md, "Point masses"): symplectic Euler on an undamped
// oscillator is stable for h omega < 2 and its energy error is about h omega / 2, so 0.25 keeps
// both far off; explicit damping is stable for h c/m < 2.
constexpr double kMaxStepTimesOmega = 0.25;
constexpr double kMaxStepTimesDampingRate = 0.5;

// Largest eigenvalue of M^-1 A for the chain's symmetric 2x2 matrix A = [[a, -b], [-b, d]] and
// M = diag(m0, m1). M^-1 A is similar to the symmetric M^-1/2 A M^-1/2, so its eigenvalues are real.
double largest_eigenvalue(double a, double b, double d, double m0, double m1) noexcept {
  const double half_trace = 0.5 * (a / m0 + d / m1);
  const double det = (a * d - b * b) / (m0 * m1);
  return half_trace + std::sqrt(std::max(0.0, half_trace * half_trace - det));
}

}  // namespace

PointMassRates point_mass_rates(const schema::PointMassesTerm& term) noexcept {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const double m0 = term.mass_kg[0];
  if (!(m0 > 0)) return {kNaN, kNaN};
  const double k0 = term.stiffness_N_per_m[0], c0 = term.damping_Ns_per_m[0], cg = term.ground_damping_Ns_per_m;
  if (term.count < 2) return {std::sqrt(std::max(0.0, k0 / m0)), (c0 + cg) / m0};
  const double m1 = term.mass_kg[1];
  if (!(m1 > 0)) return {kNaN, kNaN};
  const double k1 = term.stiffness_N_per_m[1], c1 = term.damping_Ns_per_m[1];
  return {std::sqrt(std::max(0.0, largest_eigenvalue(k0 + k1, k1, k1, m0, m1))),
          largest_eigenvalue(c0 + c1 + cg, c1, c1 + cg, m0, m1)};
}

double max_point_mass_substep_s(const schema::PointMassesTerm& term) noexcept {
  const PointMassRates rates = point_mass_rates(term);
  if (!std::isfinite(rates.omega_max_rad_s) || !std::isfinite(rates.damping_rate_max_per_s)) return 0;
  double step = std::numeric_limits<double>::infinity();
  if (rates.omega_max_rad_s > 0) step = std::min(step, kMaxStepTimesOmega / rates.omega_max_rad_s);
  if (rates.damping_rate_max_per_s > 0) step = std::min(step, kMaxStepTimesDampingRate / rates.damping_rate_max_per_s);
  return step;
}

std::uint32_t point_mass_substeps(double max_substep_s, double dt_s) noexcept {
  if (!(dt_s > 0) || !std::isfinite(dt_s)) return 0;
  if (!(max_substep_s > 0)) return std::numeric_limits<std::uint32_t>::max();
  const double needed = std::ceil(dt_s / max_substep_s);  // 0 only if max is infinite
  if (needed >= static_cast<double>(std::numeric_limits<std::uint32_t>::max()))
    return std::numeric_limits<std::uint32_t>::max();
  return std::max<std::uint32_t>(1, static_cast<std::uint32_t>(needed));
}

PointMassesState point_masses_at_rest(const schema::PointMassesTerm& term, glm::dvec2 hand_m) noexcept {
  const glm::dvec2 g{term.gravity_m_s2[0], term.gravity_m_s2[1]};
  const bool two = term.count >= 2;
  const double hanging_kg = term.mass_kg[0] + (two ? term.mass_kg[1] : 0.0);
  PointMassesState state;
  const double k0 = term.stiffness_N_per_m[0];
  state.position_m[0] = hand_m + (k0 > 0 ? hanging_kg / k0 : 0.0) * g;
  if (two) {
    const double k1 = term.stiffness_N_per_m[1];
    state.position_m[1] = state.position_m[0] + (k1 > 0 ? term.mass_kg[1] / k1 : 0.0) * g;
  }
  return state;
}

void advance_point_masses(const schema::PointMassesTerm& term, double max_substep_s, glm::dvec2 hand_m,
                          glm::dvec2 hand_m_s, double dt_s, PointMassesState& state) noexcept {
  const std::uint32_t needed = point_mass_substeps(max_substep_s, dt_s);
  if (needed == 0) return;
  const std::uint32_t steps = std::min(needed, kMaxPointMassSubsteps);
  const double h = needed > kMaxPointMassSubsteps ? max_substep_s : dt_s / steps;

  const glm::dvec2 g{term.gravity_m_s2[0], term.gravity_m_s2[1]};
  const double k0 = term.stiffness_N_per_m[0], c0 = term.damping_Ns_per_m[0];
  const double k1 = term.stiffness_N_per_m[1], c1 = term.damping_Ns_per_m[1];
  const double cg = term.ground_damping_Ns_per_m;
  const double h_over_m0 = h / term.mass_kg[0];
  glm::dvec2& x0 = state.position_m[0];
  glm::dvec2& v0 = state.velocity_m_s[0];
  glm::dvec2& x1 = state.position_m[1];
  glm::dvec2& v1 = state.velocity_m_s[1];

  if (term.count < 2) {
    for (std::uint32_t i = 0; i < steps; ++i) {
      const glm::dvec2 f0 = k0 * (hand_m - x0) + c0 * (hand_m_s - v0) - cg * v0 + term.mass_kg[0] * g;
      v0 += h_over_m0 * f0;
      x0 += h * v0;
    }
    return;
  }
  const double h_over_m1 = h / term.mass_kg[1];
  for (std::uint32_t i = 0; i < steps; ++i) {
    const glm::dvec2 link1 = k1 * (x0 - x1) + c1 * (v0 - v1);  // pulls mass 1 toward mass 0
    const glm::dvec2 f0 = k0 * (hand_m - x0) + c0 * (hand_m_s - v0) - link1 - cg * v0 + term.mass_kg[0] * g;
    const glm::dvec2 f1 = link1 - cg * v1 + term.mass_kg[1] * g;
    v0 += h_over_m0 * f0;
    v1 += h_over_m1 * f1;
    x0 += h * v0;
    x1 += h * v1;
  }
}

glm::dvec2 point_masses_hand_force(const schema::PointMassesTerm& term, const PointMassesState& state,
                                   glm::dvec2 hand_m, glm::dvec2 hand_m_s) noexcept {
  return -term.stiffness_N_per_m[0] * (hand_m - state.position_m[0]) -
         term.damping_Ns_per_m[0] * (hand_m_s - state.velocity_m_s[0]);
}

}  // namespace sandpaper::runtime
