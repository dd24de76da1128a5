#include <algorithm>
#include <cmath>
#include <variant>

#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::schema {

bool is_passive(const Term& term) {
  if (const auto* d = std::get_if<DamperTerm>(&term)) return d->damping_Ns_per_m >= 0;
  if (const auto* f = std::get_if<LinearFieldTerm>(&term)) return f->tangential_N_per_m == 0;
  // ATNSpring pushes the hand away from a point that lags it, so along its recent motion: active.
  // Minus (k (J - M), M ahead of the hand) is a damper plus an added mass, passive in continuous
  // time; it stays metered because its acceleration is a finite difference of sampled positions,
  // and a delayed acceleration feedback can put energy in (docs/TEXTURES.md, "Minus and ATNSpring").
  return !std::holds_alternative<NapTerm>(term) && !std::holds_alternative<MinusTerm>(term) &&
         !std::holds_alternative<AttractorTerm>(term) && !std::holds_alternative<FollowerSpringTerm>(term);
}

bool has_state(const Term& term) {
  return std::holds_alternative<FollowerSpringTerm>(term) || std::holds_alternative<PointMassesTerm>(term) ||
         std::holds_alternative<AttractorTerm>(term) || std::holds_alternative<FrictionTerm>(term);
}

std::uint32_t point_mass_substeps(const PointMassesTerm& t, double dt_s) {
  if (!(dt_s > 0) || t.count < 1 || t.count > 2) return 1;
  // Row sums of M^-1 K and M^-1 C bound their largest eigenvalues (Gershgorin).
  const bool two = t.count == 2;
  const double k0 = t.stiffness_N_per_m[0], k1 = two ? t.stiffness_N_per_m[1] : 0;
  const double c0 = t.damping_Ns_per_m[0], c1 = two ? t.damping_Ns_per_m[1] : 0, cg = t.ground_damping_Ns_per_m;
  double omega2 = (k0 + 2 * k1) / t.mass_kg[0];
  double rate = (c0 + 2 * c1 + cg) / t.mass_kg[0];
  if (two) {
    omega2 = std::max(omega2, 2 * k1 / t.mass_kg[1]);
    rate = std::max(rate, (2 * c1 + cg) / t.mass_kg[1]);
  }
  const double n = std::max({1.0, std::ceil(dt_s * std::sqrt(std::max(omega2, 0.0)) / 0.25), std::ceil(dt_s * rate / 0.5)});
  return n > 1e9 || !std::isfinite(n) ? 1000000000u : static_cast<std::uint32_t>(n);
}

}  // namespace sandpaper::schema
