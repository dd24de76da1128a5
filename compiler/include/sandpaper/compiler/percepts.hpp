#pragma once
// The perceptual words besides roughness: viscosity (stickiness), slipperiness, softness
// (springiness) and bumpiness. Each compiles through its percept's compile map in
// calibration/maps/ (or the device's own map): softness, viscosity and slipperiness through maps
// from the literature (W0321 where their source felt real materials), bumpiness through a
// provisional one (W0320). schema/LANGUAGE.md, "Other perceptual words"; docs/CALIBRATION.md.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

// One word of the language and the physical parameter its percept sets.
struct PerceptWord {
  const char* word;        // as written: "stickiness"
  const char* percept;     // the map's percept: "viscosity" (stickiness is an alias)
  const char* parameter;   // the provenance name of what it sets: "damper.damping"
  const char* quantity;    // for the one-statement-per-quantity rule: "the damping"
  const char* what;        // in explain: "damping b"
  const char* si_unit;     // of the parameter: "N*s/m"
  const char* physical;    // the physical statement for the same thing, for suggestions: "damper 2 N*s/m"
  // Why 0 is refused, or nullptr when 0 is allowed (0 = no damping; softness 0 = infinitely stiff).
  const char* zero_refused;
};

// Every perceptual word except roughness, in the order schema/LANGUAGE.md lists them.
const std::vector<PerceptWord>& percept_words();
// nullptr if `word` is not one of them.
const PerceptWord* find_percept_word(std::string_view word);

// The range of a map's ratio predictor (SI) from its [domain]; nullopt if the map gives none.
std::optional<calibration::Range> ratio_domain(const calibration::PsychophysicalMap& map);

// Codegen for perceptual targets: the Coulomb friction term of `slipperiness` (one coefficient, the
// hand pressing with 1 N), one provenance record per target ("damper.viscosity_target", ratio scale,
// naming its map and the map's file), W0320 for each target whose map is provisional and W0321 for
// each whose map's source felt real materials. The parameters they set (damping, stiffness, period)
// are recorded where those are generated.
void generate_percepts(const ResolvedMaterial& m, schema::PatchProgram& out, Diagnostics& diags);

// explain's perceptual layer for these targets: one entry each, with its map's formula and file.
// `inline_first`: the first entry continues the "perceptual" line (no roughness was printed on it).
// Each target's map is followed by its source, its domain and its JND step, where the map gives one.
std::string explain_percepts(const ResolvedMaterial& m, const calibration::CalibrationSet& cal, bool inline_first);
// The same as JSON (explain --json "percepts"): per target its word, value, the parameter it set (SI,
// unit) and the map with its citation, domain (range in the parameter's unit, apparatus, effector)
// and Weber fraction.
nlohmann::json percepts_json(const ResolvedMaterial& m, const calibration::CalibrationSet& cal);
// "20 N/m to 200 N/m; real material, fingers squeezing": the map's ratio-predictor range and what
// its source's subjects touched.
std::string domain_text(const calibration::PsychophysicalMap& map, const char* si_unit);

}  // namespace sandpaper::compiler
