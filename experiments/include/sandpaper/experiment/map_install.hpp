// What installing a fitted device map would change: the named levels of its percept and the library
// entries that write its word, compiled for the device before and after (docs/EXPERIMENTS.md, step 7).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/compiler.hpp"

namespace sandpaper::experiment {

// One compile: whether it compiled, the percept's parameter (SI, 0 when it did not compile) and the
// codes of its diagnostics in order.
struct CompileOutcome {
  bool ok = false;
  double value_si = 0;
  std::vector<std::string> codes;
};

struct MapChange {
  std::string kind;   // "level" or "library"
  std::string name;   // "very-thick", or the library entry's name
  std::string text;   // what was compiled: "viscosity very-thick"
  std::string unit;   // of value_si: "N*s/m"
  CompileOutcome before, after;
  bool breaks() const { return before.ok && !after.ok; }
  // Breaks, starts to compile, asks for another value (relative 1e-6) or warns differently.
  bool changed() const;
};

// The calibration in `dir` with `map_text` installed as maps/`file_name`, in place of any map with
// the same file name or id and of any device map of the same device and percept. Loaded from a
// temporary copy, removed before returning. Throws calibration::CalibrationError.
calibration::CalibrationSet calibration_with_map(const std::filesystem::path& dir, const std::string& file_name,
                                                 const std::string& map_text, const calibration::PsychophysicalMap& map);

// Every named level of `percept`, and every library entry with a statement of its word (or an alias),
// compiled by `before` and by `after` (the same device, library and options, another calibration).
std::vector<MapChange> map_changes(const compiler::Compiler& before, const compiler::Compiler& after,
                                   const std::string& percept);

// The ratio predictor's values (SI) of the named levels of `percept` through `map`.
std::vector<double> level_values(const calibration::CalibrationSet& cal, const calibration::PsychophysicalMap& map);

nlohmann::json map_changes_json(const std::vector<MapChange>& changes);
// One line per change: "level viscosity very-thick: 10 N*s/m (W0321) -> E0303: breaks".
std::string map_changes_text(const std::vector<MapChange>& changes);

}  // namespace sandpaper::experiment
