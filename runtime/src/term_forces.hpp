#pragma once
// The force of each term kind in closed form (Appendix B and thesis 3.2.2), one function a kind.
// Each gives the force (N) at hand position p (m, from the patch centre), velocity v (m/s) and
// acceleration a (m/s^2). The laws are stated in schema/include/sandpaper/schema/patch_program.hpp;
// the evaluator checked the parameters (periods > 0 and so on) before the first tick.
#include <cmath>
#include <numbers>

#include <glm/vec2.hpp>

#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::runtime::laws {

inline double frac(double x) noexcept { return x - std::floor(x); }

inline glm::dvec2 constant_force(const schema::ConstantForceTerm& t) noexcept { return {t.force_N[0], t.force_N[1]}; }

// Appendix B Nap: like viscosity along x, always toward +y along y (velvet's nap).
inline glm::dvec2 nap(const schema::NapTerm& t, glm::dvec2 v) noexcept {
  return {-t.damping_Ns_per_m * v.x, std::abs(t.damping_Ns_per_m * v.y)};
}

// One axis of a periodic law at coordinate u (m).
inline double periodic_axis(const schema::PeriodicTerm& t, double u) noexcept {
  switch (t.shape) {
    case schema::PeriodicShape::Sine: return -t.amplitude_N * std::sin(2 * std::numbers::pi * u / t.period_m);
    case schema::PeriodicShape::Sawtooth: return t.amplitude_N * (2 * frac(std::abs(u) / t.period_m) - 1);
    case schema::PeriodicShape::Triangle: return -t.amplitude_N * (2 * frac(u / t.period_m) - 1);
  }
  return 0;
}

inline glm::dvec2 periodic(const schema::PeriodicTerm& t, glm::dvec2 p) noexcept {
  return {t.on_x ? periodic_axis(t, p.x) : 0.0, t.on_y ? periodic_axis(t, p.y) : 0.0};
}

// Appendix B Ridge, with a floored modulo so that the ridges repeat the same way on both sides of
// the centre.
inline glm::dvec2 ridge(const schema::RidgeTerm& t, glm::dvec2 p) noexcept {
  return {t.stiffness_N_per_m * (t.wavelength_m * frac(p.x / t.wavelength_m) - t.ridge_width_m), 0.0};
}

inline glm::dvec2 bowl(const schema::BowlTerm& t, glm::dvec2 p) noexcept {
  return -t.stiffness_N_per_m * std::sqrt(std::hypot(p.x, p.y) / t.radius_m) * p;
}

inline glm::dvec2 linear_field(const schema::LinearFieldTerm& t, glm::dvec2 p) noexcept {
  return t.radial_N_per_m * p + t.tangential_N_per_m * glm::dvec2{-p.y, p.x};
}

inline glm::dvec2 linear_spring(const schema::LinearSpringTerm& t, glm::dvec2 p) noexcept {
  const glm::dvec2 n{std::cos(t.orientation_rad), std::sin(t.orientation_rad)};
  const double along = (p.x - t.centre_m[0]) * n.x + (p.y - t.centre_m[1]) * n.y;
  return -t.stiffness_N_per_m * along * n;
}

// Appendix B Minus: F = k (J - M), M where the hand will be `lead` from now, M - J = v lead + a lead^2 / 2
// (docs/TEXTURES.md, "Minus and ATNSpring": the OCR's x component).
inline glm::dvec2 minus(const schema::MinusTerm& t, glm::dvec2 v, glm::dvec2 a) noexcept {
  return -t.stiffness_N_per_m * (t.lead_s * v + (0.5 * t.lead_s * t.lead_s) * a);
}

// Appendix B ATNSpring: F = k (J - M), M a point that follows the hand with a lag: the hand is pushed
// away from where it has just been (docs/TEXTURES.md, "Minus and ATNSpring").
inline glm::dvec2 follower_spring(const schema::FollowerSpringTerm& t, glm::dvec2 p, glm::dvec2 follower_m) noexcept {
  return t.stiffness_N_per_m * (p - follower_m);
}

// Friction (docs/FORCE_LAWS.md, "Friction"): the spring to the adhesion point.
inline glm::dvec2 friction(const schema::FrictionTerm& t, glm::dvec2 p, glm::dvec2 adhesion_m) noexcept {
  return -t.stiffness_N_per_m * (p - adhesion_m);
}

// Advances the adhesion point w over one tick (Karnopp 1985's stick band, Hayward & Armstrong 2000's
// adhesion point): stuck until |p - w| passes mu_static P / k; sliding, w trails the hand at
// mu_kinetic P / k until the hand turns back or slows below the stick speed. w only moves toward p.
// z_static and z_kinetic are the stick band's two stretches, mu P / k (m).
inline void advance_adhesion(glm::dvec2 p, glm::dvec2 v, double stick_speed_m_s, double z_static, double z_kinetic,
                             glm::dvec2& w, bool& sticking) noexcept {
  const glm::dvec2 z = p - w;
  const double r = std::hypot(z.x, z.y);
  if (!sticking && (std::hypot(v.x, v.y) < stick_speed_m_s || v.x * z.x + v.y * z.y <= 0)) sticking = true;
  if (sticking && r > z_static) sticking = false;  // breaks loose
  if (!sticking && r > z_kinetic) w = p - (z_kinetic / r) * z;
}

inline void advance_friction(const schema::FrictionTerm& t, glm::dvec2 p, glm::dvec2 v, glm::dvec2& w, bool& sticking) noexcept {
  const double per_mu = t.press_N / t.stiffness_N_per_m;
  advance_adhesion(p, v, t.stick_speed_m_s, t.static_coefficient * per_mu, t.kinetic_coefficient * per_mu, w, sticking);
}

// How far the way p - w points against the nap: 0 along n (with the nap), 1 along -n, (1 - cos) / 2
// between. With the hand on w the way is undefined and nothing depends on it (no stretch to compare).
inline double against_nap(const schema::NapFrictionTerm& t, glm::dvec2 z) noexcept {
  const double r = std::hypot(z.x, z.y);
  if (!(r > 0)) return 0;
  const double c = (z.x * std::cos(t.nap_orientation_rad) + z.y * std::sin(t.nap_orientation_rad)) / r;
  return 0.5 * (1 - c);
}

// As advance_friction, the coefficients mixed by the way the hand is pulling from w. w moves along
// p - w, so the way, and the coefficients, stay those the move was judged with.
inline void advance_nap_friction(const schema::NapFrictionTerm& t, glm::dvec2 p, glm::dvec2 v, glm::dvec2& w,
                                 bool& sticking) noexcept {
  const double a = against_nap(t, p - w);
  const double mu_s = t.static_coefficient + a * (t.against_static_coefficient - t.static_coefficient);
  const double mu_k = t.kinetic_coefficient + a * (t.against_kinetic_coefficient - t.kinetic_coefficient);
  const double per_mu = t.press_N / t.stiffness_N_per_m;
  advance_adhesion(p, v, t.stick_speed_m_s, mu_s * per_mu, mu_k * per_mu, w, sticking);
}

// Where the attractor's light object is at time t_s on its swirling path (thesis 3.2.2).
inline glm::dvec2 attractor_point(const schema::AttractorTerm& t, double t_s) noexcept {
  const double theta = 2 * std::numbers::pi * t_s / t.period_s;
  const double r = t.radius_m * (1 + t.swirl * std::sin(3 * theta)) / (1 + t.swirl);
  return {t.centre_m[0] + r * std::cos(theta), t.centre_m[1] + r * std::sin(theta)};
}

inline glm::dvec2 attractor(const schema::AttractorTerm& t, glm::dvec2 p, double t_s) noexcept {
  return -t.stiffness_N_per_m * (p - attractor_point(t, t_s));
}

}  // namespace sandpaper::runtime::laws
