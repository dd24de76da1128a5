#include "sandpaper/experiment/percept_quantity.hpp"

#include <array>
#include <variant>

namespace sandpaper::experiment {
namespace {

constexpr std::array kQuantities{
    PerceptQuantity{"roughness", "force", "N", "maximum lateral force of the stimulus", "compiled_force_N",
                    "How rough was it", "larger = rougher", "a texture with a lateral force"},
    PerceptQuantity{"softness", "stiffness", "N/m", "stiffness k of the spring F = -k p", "stiffness_N_per_m",
                    "How soft was it", "larger = softer", "a spring (spring K N/m, or softness)"},
    PerceptQuantity{"viscosity", "damping", "N*s/m", "damping b of the damper F = -b v", "damping_N_s_per_m",
                    "How viscous was it", "larger = more viscous", "a damper (damper B N*s/m, or viscosity)"},
    PerceptQuantity{"slipperiness", "friction", "1", "friction coefficient mu, the hand pressing with 1 N",
                    "friction_coefficient", "How slippery was it", "larger = more slippery",
                    "Coulomb friction (physics Friction, or slipperiness)"},
};

}  // namespace

const PerceptQuantity* find_percept_quantity(std::string_view percept) {
  for (const auto& q : kQuantities)
    if (percept == q.percept) return &q;
  return nullptr;
}

std::string percept_quantity_names() {
  std::string out;
  for (const auto& q : kQuantities) out += (out.empty() ? "" : ", ") + std::string(q.percept);
  return out;
}

std::optional<double> stimulus_quantity(const PerceptQuantity& q, const schema::PatchProgram& program) {
  const std::string_view p = q.predictor;
  if (p == "force") return program.max_lateral_force_N > 0 ? std::optional<double>(program.max_lateral_force_N) : std::nullopt;
  double sum = 0;
  bool found = false;
  for (const auto& term : program.terms) {
    if (const auto* s = std::get_if<schema::SpringTerm>(&term); s && p == "stiffness") sum += s->stiffness_N_per_m, found = true;
    if (const auto* d = std::get_if<schema::DamperTerm>(&term); d && p == "damping" && d->damping_Ns_per_m > 0)
      sum += d->damping_Ns_per_m, found = true;
    if (const auto* f = std::get_if<schema::FrictionTerm>(&term); f && p == "friction") sum += f->kinetic_coefficient, found = true;
  }
  return found && sum > 0 ? std::optional<double>(sum) : std::nullopt;
}

calibration::FitPredictor fit_predictor(const PerceptQuantity& q) { return {q.predictor, q.unit, q.quantity}; }

}  // namespace sandpaper::experiment
