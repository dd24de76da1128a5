#pragma once
// The physics patch of one or two point masses on springs and dampers (thesis 3.2.2, "one
// point-mass and two point-masses coupled to the user by springs"), integrated by fixed-step
// semi-implicit (symplectic) Euler. The law itself is schema::PointMassesTerm; docs/RUNTIME.md,
// "Point masses", gives the step rule. Everything here is pure and allocation-free.
#include <cstdint>

#include <glm/vec2.hpp>

#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::runtime {

// Most substeps one servo tick spends on one point-masses term. A tick that would need more (a long
// stall, or a material too stiff for the servo rate) runs this many substeps of the largest stable
// step, so the masses fall behind the wall clock for that tick instead of going unstable. The
// compiler refuses materials that need more than this at the device's minimum servo rate (its
// estimate, schema::point_mass_substeps, bounds omega by Gershgorin's theorem, never below this file's
// exact eigenvalues, so what it accepts the runtime integrates within the cap).
inline constexpr std::uint32_t kMaxPointMassSubsteps = schema::kMaxPointMassSubsteps;

// Positions (m, patch coordinates) and velocities (m/s) of the masses; index 1 unused if count = 1.
struct PointMassesState {
  glm::dvec2 position_m[2]{{0, 0}, {0, 0}};
  glm::dvec2 velocity_m_s[2]{{0, 0}, {0, 0}};
};

// The fastest rates of the chain with the hand held still: omega_max (rad/s), the largest natural
// frequency (sqrt of the largest eigenvalue of M^-1 K), and the largest damping rate (1/s, largest
// eigenvalue of M^-1 C, ground damping included). Non-finite for a term with a zero or negative mass.
struct PointMassRates {
  double omega_max_rad_s = 0;
  double damping_rate_max_per_s = 0;
};
PointMassRates point_mass_rates(const schema::PointMassesTerm& term) noexcept;

// Largest substep h (s) with h * omega_max <= 0.25 and h * damping_rate_max <= 0.5; +infinity for a
// term with no springs and no dampers. Zero for a term with non-finite rates.
double max_point_mass_substep_s(const schema::PointMassesTerm& term) noexcept;

// Substeps a tick of `dt_s` needs so that each is at most `max_substep_s`: ceil(dt / max), at least
// 1 for dt > 0, 0 for dt <= 0 or not finite. Not capped: compare with kMaxPointMassSubsteps.
// Saturates at UINT32_MAX.
std::uint32_t point_mass_substeps(double max_substep_s, double dt_s) noexcept;

// The state at rest under gravity with the hand held at `hand_m`: mass 0 sits (m0 + m1) g / k0 from
// the hand, mass 1 sits m1 g / k1 from mass 0 (a link without a spring adds no offset).
PointMassesState point_masses_at_rest(const schema::PointMassesTerm& term, glm::dvec2 hand_m) noexcept;

// Advances `state` by dt_s with the hand held at position `hand_m` and velocity `hand_m_s` (the
// servo tick's sample, held over the tick): point_mass_substeps(max_substep_s, dt_s) steps of
// semi-implicit Euler (velocities first, then positions with the new velocities), capped at
// kMaxPointMassSubsteps steps of max_substep_s. dt_s <= 0 leaves the state unchanged.
void advance_point_masses(const schema::PointMassesTerm& term, double max_substep_s, glm::dvec2 hand_m,
                          glm::dvec2 hand_m_s, double dt_s, PointMassesState& state) noexcept;

// The force on the hand from link 0 (N): F = -k0 (p - x0) - c0 (v - v0).
glm::dvec2 point_masses_hand_force(const schema::PointMassesTerm& term, const PointMassesState& state,
                                   glm::dvec2 hand_m, glm::dvec2 hand_m_s) noexcept;

}  // namespace sandpaper::runtime
