// The API's exceptions and the Material handle.
#include <algorithm>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/sandpaper.hpp"

namespace sandpaper {
namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  return list;
}

// A percept with no levels is named as the unknown part, with the percepts that have levels.
std::string level_message(const std::string& percept, const std::string& name, const std::vector<std::string>& known,
                          const std::vector<std::string>& level_percepts) {
  if (known.empty()) {
    std::string message = "unknown percept \"" + percept + "\": no levels are named for it; percepts with levels: " +
                          (level_percepts.empty() ? std::string("none") : joined(level_percepts));
    if (auto close = compiler::closest_match(percept, level_percepts); !close.empty())
      message += " (did you mean \"" + close + "\"?)";
    return message;
  }
  std::string message = "unknown " + percept + " level \"" + name + "\"; known levels: " + joined(known);
  if (auto close = compiler::closest_match(name, known); !close.empty()) message += " (did you mean \"" + close + "\"?)";
  return message;
}

}  // namespace

CompileError::CompileError(compiler::Diagnostics diagnostics)
    : Error(compiler::format_diagnostics(diagnostics)), diagnostics_(std::move(diagnostics)) {}

UnknownLevel::UnknownLevel(std::string name, std::vector<std::string> known, const std::string& percept,
                           const std::vector<std::string>& level_percepts)
    : Error(level_message(percept, name, known, level_percepts)), name_(std::move(name)), known_(std::move(known)) {}

std::vector<std::string> percepts_with_levels(const calibration::CalibrationSet& calibration) {
  // Every level file names a map (the calibration refuses one whose map is missing), so the maps'
  // percepts cover every percept with levels.
  std::vector<std::string> out;
  for (const auto& map : calibration.maps())
    if (!calibration.levels(map.percept).empty() && std::find(out.begin(), out.end(), map.percept) == out.end())
      out.push_back(map.percept);
  std::sort(out.begin(), out.end());
  return out;
}

Material::Material(schema::PatchProgram program)
    : program_(std::make_shared<const schema::PatchProgram>(std::move(program))) {}

std::vector<std::string> Material::warnings() const {
  std::vector<std::string> out;
  for (const auto& w : program_->warnings) out.push_back(w.message + " [" + w.code + "]");
  return out;
}

}  // namespace sandpaper
