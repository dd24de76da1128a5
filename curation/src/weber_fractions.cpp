#include "sandpaper/curation/weber_fractions.hpp"

#include <cmath>
#include <cstring>

namespace sandpaper::curation {

double WeberFractions::for_term(const std::string& key) const {
  const auto ends = [&](const char* s) { return key.size() >= std::strlen(s) && key.compare(key.size() - std::strlen(s), std::string::npos, s) == 0; };
  if (key == "spring.stiffness_N_per_m") return stiffness;
  if (key == "damper.damping_Ns_per_m") return damping;
  if ((key.rfind("friction.", 0) == 0 || key.rfind("nap_friction.", 0) == 0) && ends("coefficient")) return friction;
  return force;
}

WeberFractions weber_fractions_of(const calibration::CalibrationSet& cal) {
  WeberFractions w(cal.knowledge().force_jnd.weber_fraction);
  const auto of = [&](const char* percept, double& out) {
    if (const auto* m = cal.default_compile_map(percept); m && m->weber_fraction) out = *m->weber_fraction;
  };
  of("softness", w.stiffness);
  of("viscosity", w.damping);
  of("slipperiness", w.friction);
  return w;
}

std::array<std::optional<double>, 3> law_coordinates(const std::vector<std::pair<std::string, double>>& term_params,
                                                     const WeberFractions& w) {
  std::array<std::optional<double>, 3> out;
  const std::array<std::pair<const char*, double>, 3> dims{{{"spring.stiffness_N_per_m", w.stiffness},
                                                            {"damper.damping_Ns_per_m", w.damping},
                                                            {"friction.kinetic_coefficient", w.friction}}};
  for (std::size_t d = 0; d < dims.size(); ++d)
    for (const auto& [k, v] : term_params)
      if (k == dims[d].first && v > 0) {
        out[d] = std::log(v) / std::log1p(dims[d].second);
        break;
      }
  return out;
}

bool WeberFractions::valid() const {
  for (double w : {force, stiffness, damping, friction})
    if (!(w > 0 && w <= 1)) return false;
  return true;
}

}  // namespace sandpaper::curation
