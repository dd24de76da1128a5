#pragma once
// What a magnitude-estimation design scales, and the physical quantity of each stimulus it is
// regressed on: roughness on the maximum lateral force (Minsky 1995, Figure 19), softness on the
// spring's stiffness, viscosity on the damper's damping, slipperiness on the friction coefficient
// (docs/CALIBRATION.md, the maps of each). The predictor names are the map file's.
#include <optional>
#include <string>
#include <string_view>

#include "sandpaper/calibration/fit.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::experiment {

struct PerceptQuantity {
  const char* percept;       // "softness": the design's `percept`, the map's percept
  const char* predictor;     // "stiffness": the map's predictor name
  const char* unit;          // SI unit of the predictor: "N/m"; "1" for the friction coefficient
  const char* quantity;      // in words, for the map and the picture
  const char* results_key;   // the answer record's per-stimulus key: "stiffness_N_per_m"
  const char* question;      // the subject is asked: "How soft was it"
  const char* more;          // "larger = softer"
  const char* law;           // the term a stimulus must have: "a spring (F = -k p)"
};

// nullptr for a percept no design can scale.
const PerceptQuantity* find_percept_quantity(std::string_view percept);
// "roughness, softness, viscosity, slipperiness"
std::string percept_quantity_names();
// The stimulus program's value of the predictor (SI): the sum of its springs' stiffnesses, its
// dampers' damping (positive dampers only), its Coulomb friction's kinetic coefficient; for
// roughness its maximum lateral force. nullopt when the program has no such term.
std::optional<double> stimulus_quantity(const PerceptQuantity& q, const schema::PatchProgram& program);
calibration::FitPredictor fit_predictor(const PerceptQuantity& q);

}  // namespace sandpaper::experiment
