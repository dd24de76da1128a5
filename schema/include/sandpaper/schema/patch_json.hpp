#pragma once
// JSON views of a patch program (for `sandpaper compile|explain|inspect --json`). Key names carry
// their units (`period_m`); a compiled value says so (`compiled_max_lateral_force_N`), as a run's
// report says `felt_...`; see docs/PATCH_FORMAT.md.
#include <nlohmann/json.hpp>

#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::schema {

// Summary of the program: material, device, size, max force, roughness, warnings, per-parameter
// provenance (an object keyed by parameter), and one entry per term with its parameters.
// `with_tables` adds the force tables themselves (large).
nlohmann::json to_json(const PatchProgram& p, bool with_tables = false);

// Display form of an SI value: metres as mm, radians as deg, fractions as %, others as is.
std::string display_value(double value_si, const std::string& si_unit);

// A ratio-scale roughness for people: three significant digits ("0.452", "0.05", "1"), as every
// human-readable output prints it (the CLI, explain, the catalog); JSON keeps every digit.
std::string roughness_text(double roughness);

}  // namespace sandpaper::schema
