#include <variant>

#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::schema {

bool is_passive(const Term& term) {
  if (const auto* d = std::get_if<DamperTerm>(&term)) return d->damping_Ns_per_m >= 0;
  if (const auto* f = std::get_if<LinearFieldTerm>(&term)) return f->tangential_N_per_m == 0;
  return !std::holds_alternative<NapTerm>(term) && !std::holds_alternative<MinusTerm>(term) &&
         !std::holds_alternative<AttractorTerm>(term);
}

bool has_state(const Term& term) {
  return std::holds_alternative<FollowerSpringTerm>(term) || std::holds_alternative<PointMassesTerm>(term) ||
         std::holds_alternative<AttractorTerm>(term);
}

}  // namespace sandpaper::schema
