#include <algorithm>
#include <cmath>
#include <variant>

#include "sandpaper/schema/patch_program.hpp"
#include "sandpaper/schema/term_kinds.hpp"

namespace sandpaper::schema {

bool is_passive(const Term& term) {
  return terms::visit_kind(term, [](const auto& kind, const auto& t) { return kind.passive(t); });
}

bool has_state(const Term& term) {
  return terms::visit_kind(term, [](const auto& kind, const auto&) { return kind.has_state; });
}

std::uint64_t grid_bytes(const PatchProgram& program) {
  std::uint64_t floats = 0;
  for (const auto& term : program.terms) {
    if (const auto* h = std::get_if<HeightFieldTerm>(&term)) floats += h->force_x_N.size() + h->force_y_N.size();
    if (const auto* g = std::get_if<GratingTerm>(&term)) floats += g->force_N.size();
  }
  return floats * sizeof(float);
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
