#pragma once
// `sandpaper library check` (docs/LIBRARY.md lists the codes): validates every entry of a
// library as data (names, metadata, sources, `like` graph) and by compiling it for every device of
// the calibration, and warns about entries of one family the thesis' knowledge cannot tell apart.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/curation/licences.hpp"
#include "sandpaper/curation/progress.hpp"

namespace sandpaper::curation {

struct CheckOptions {
  std::filesystem::path library_dir;       // empty: compiler::default_library_dir()
  std::filesystem::path calibration_dir;   // empty: calibration::default_calibration_dir()
  std::vector<std::string> devices;        // empty: every device of the calibration
  // A layered library, front first: each root is checked against the roots below it (its `like`
  // resolves through them; an entry hiding one below warns unless it says `overrides`). When set,
  // library_dir is not used.
  std::vector<std::filesystem::path> library_path;
  std::string root;                        // check only the root with this id (empty: every root)
  // The front root's entry files (relative to it) that were there before the change being checked
  // (library review: the base commit's). In a clash of names (E0607) these are established and the
  // other file is the newcomer. Unset: the file git committed first (when the root is in a git work
  // tree), else the one the root's index lists, else the first in path order.
  std::optional<std::set<std::string>> established = std::nullopt;
};

struct CheckResult {
  compiler::Diagnostics diagnostics;  // errors E06xx (and the compiler's own codes for syntax), warnings W06xx
  // The compiler's warnings that entries accept (`accept CODE "reason"`), as notes with the
  // warning's code and the reason; one per warning as `diagnostics` would have had it.
  compiler::Diagnostics accepted;
  std::size_t entries = 0;
  std::vector<std::string> devices;   // the devices compiled for
  std::set<std::string> uncalibrated; // of them, those whose force scale is assumed (W0331, said once here, not per entry)
  std::size_t errors() const;
  std::size_t warnings() const;
  // "checked 64 entries on 3 devices: 0 errors, 2 warnings" (then ", 5 accepted" if any are)
  std::string summary() const;
};

// Throws calibration::CalibrationError when the calibration cannot be read and std::invalid_argument
// for an unknown device in `devices`. Problems of the library itself are diagnostics, never exceptions.
CheckResult check_library(const CheckOptions& options, Progress& progress);


}  // namespace sandpaper::curation
