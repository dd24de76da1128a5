#include "term_checks.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <stdexcept>
#include <string>
#include <variant>

namespace sandpaper::runtime {
namespace {

using namespace schema;

// Checks the parameters of one term; every failure names the term's index and kind.
class TermCheck {
 public:
  TermCheck(std::size_t index, const char* kind) : index_(index), kind_(kind) {}

  void finite(const char* what, double x) const {
    if (!std::isfinite(x)) fail(std::string(what) + " must be finite");
  }
  void positive(const char* what, double x) const {
    if (!(std::isfinite(x) && x > 0)) fail(std::string(what) + " must be positive and finite");
  }
  void non_negative(const char* what, double x) const {
    if (!(std::isfinite(x) && x >= 0)) fail(std::string(what) + " must be zero or more, and finite");
  }
  [[noreturn]] void fail(const std::string& why) const {
    throw std::invalid_argument("term " + std::to_string(index_) + " (" + kind_ + "): " + why);
  }

 private:
  std::size_t index_;
  const char* kind_;
};

void check(const TermCheck& c, const SpringTerm& t) {
  c.finite("stiffness", t.stiffness_N_per_m);
  c.finite("centre x", t.centre_m[0]);
  c.finite("centre y", t.centre_m[1]);
}

void check(const TermCheck& c, const DamperTerm& t) { c.finite("damping", t.damping_Ns_per_m); }

void check(const TermCheck& c, const GratingTerm& t) {
  c.positive("period", t.period_m);
  c.finite("orientation", t.orientation_rad);
  if (t.force_N.size() < 2) c.fail("force table needs at least 2 samples");
}

void check(const TermCheck& c, const HeightFieldTerm& t) {
  const std::size_t samples = std::size_t{t.nx} * t.ny;
  if (samples == 0) c.fail("grid is empty");
  if (t.force_x_N.size() != samples || t.force_y_N.size() != samples)
    c.fail("force tables must hold nx * ny samples");
  c.positive("spacing x", t.spacing_m[0]);
  c.positive("spacing y", t.spacing_m[1]);
  c.finite("origin x", t.origin_m[0]);
  c.finite("origin y", t.origin_m[1]);
}

void check(const TermCheck& c, const ConstantForceTerm& t) {
  c.finite("force x", t.force_N[0]);
  c.finite("force y", t.force_N[1]);
}

void check(const TermCheck& c, const NapTerm& t) { c.finite("damping", t.damping_Ns_per_m); }

void check(const TermCheck& c, const PeriodicTerm& t) {
  if (t.shape != PeriodicShape::Sine && t.shape != PeriodicShape::Sawtooth && t.shape != PeriodicShape::Triangle)
    c.fail("unknown shape " + std::to_string(static_cast<int>(t.shape)));
  c.finite("amplitude", t.amplitude_N);
  c.positive("period", t.period_m);
}

void check(const TermCheck& c, const RidgeTerm& t) {
  c.finite("stiffness", t.stiffness_N_per_m);
  c.positive("wavelength", t.wavelength_m);
  c.finite("ridge width", t.ridge_width_m);
}

void check(const TermCheck& c, const BowlTerm& t) {
  c.finite("stiffness", t.stiffness_N_per_m);
  c.positive("radius", t.radius_m);
}

void check(const TermCheck& c, const LinearFieldTerm& t) {
  c.finite("radial gain", t.radial_N_per_m);
  c.finite("tangential gain", t.tangential_N_per_m);
}

void check(const TermCheck& c, const LinearSpringTerm& t) {
  c.finite("stiffness", t.stiffness_N_per_m);
  c.finite("orientation", t.orientation_rad);
  c.finite("centre x", t.centre_m[0]);
  c.finite("centre y", t.centre_m[1]);
}

void check(const TermCheck& c, const MinusTerm& t) {
  c.finite("stiffness", t.stiffness_N_per_m);
  c.non_negative("lead", t.lead_s);
}

// ATNSpring is active and metered by the energy tank (docs/TEXTURES.md); a negative stiffness would
// turn it into a different law (a spring in series with a damper) that the library does not name.
void check(const TermCheck& c, const FollowerSpringTerm& t) {
  c.non_negative("stiffness", t.stiffness_N_per_m);
  c.positive("lag", t.lag_s);
}

// The kinetic coefficient above the static one would make the contact slide at more force than it took
// to break it loose (docs/FORCE_LAWS.md, "Friction").
void check(const TermCheck& c, const FrictionTerm& t) {
  c.finite("static coefficient", t.static_coefficient);
  c.finite("kinetic coefficient", t.kinetic_coefficient);
  c.finite("press", t.press_N);
  c.finite("stiffness", t.stiffness_N_per_m);
  c.finite("stick speed", t.stick_speed_m_s);
  c.non_negative("static coefficient", t.static_coefficient);
  c.non_negative("kinetic coefficient", t.kinetic_coefficient);
  if (t.kinetic_coefficient > t.static_coefficient) c.fail("kinetic coefficient must not exceed the static one");
  c.positive("press", t.press_N);
  c.positive("stiffness", t.stiffness_N_per_m);
  c.non_negative("stick speed", t.stick_speed_m_s);
}

// Negative springs or dampers would make the masses' own motion grow without bound, which no energy
// bound on the hand could stop, and is_passive() counts this term as passive.
void check(const TermCheck& c, const PointMassesTerm& t) {
  if (t.count != 1 && t.count != 2) c.fail("count must be 1 or 2, not " + std::to_string(t.count));
  for (std::uint32_t i = 0; i < t.count; ++i) {
    const std::string n = " " + std::to_string(i);
    c.positive(("mass" + n).c_str(), t.mass_kg[i]);
    c.non_negative(("stiffness" + n).c_str(), t.stiffness_N_per_m[i]);
    c.non_negative(("damping" + n).c_str(), t.damping_Ns_per_m[i]);
  }
  c.non_negative("ground damping", t.ground_damping_Ns_per_m);
  c.finite("gravity x", t.gravity_m_s2[0]);
  c.finite("gravity y", t.gravity_m_s2[1]);
}

void check(const TermCheck& c, const AttractorTerm& t) {
  c.finite("stiffness", t.stiffness_N_per_m);
  c.non_negative("radius", t.radius_m);
  c.positive("period", t.period_s);
  c.finite("swirl", t.swirl);
  if (!(t.swirl > -1)) c.fail("swirl must be greater than -1 (the path's radius divides by 1 + swirl)");
  c.finite("centre x", t.centre_m[0]);
  c.finite("centre y", t.centre_m[1]);
}

const char* kind_name(const Term& term) {
  static constexpr const char* kNames[] = {"spring", "damper", "grating", "height field", "constant force",
                                           "nap", "periodic", "ridge", "bowl", "linear field", "linear spring",
                                           "minus", "follower spring", "point masses", "attractor", "friction"};
  static_assert(std::size(kNames) == std::variant_size_v<Term>, "a name for every term kind");
  return kNames[term.index()];
}

}  // namespace

void check_program(const PatchProgram& program) {
  for (int axis = 0; axis < 2; ++axis)
    if (!(std::isfinite(program.size_m[axis]) && program.size_m[axis] > 0))
      throw std::invalid_argument("patch size must be positive and finite");
  if (!(std::isfinite(program.energy_budget_J) && program.energy_budget_J >= 0))
    throw std::invalid_argument("energy budget must be zero or more, and finite (J)");
  if (!(std::isfinite(program.energy_refill_W) && program.energy_refill_W >= 0))
    throw std::invalid_argument("energy refill must be zero or more, and finite (W)");
  for (std::size_t i = 0; i < program.terms.size(); ++i) {
    const TermCheck c(i, kind_name(program.terms[i]));
    std::visit([&c](const auto& term) { check(c, term); }, program.terms[i]);
  }
}

}  // namespace sandpaper::runtime
