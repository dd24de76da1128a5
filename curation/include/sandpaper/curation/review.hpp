#pragma once
// `sandpaper library review`: one command for a pull request to a library kept in git
// (docs/LIBRARY.md, "Reviewing a pull request"). It asks git which files of the library changed
// since a base commit (committed, staged, unstaged or new), checks the library now and as it was at
// the base on every device, and fails on an error or a warning that is new since the base, not
// accepted, and on an entry the change touches: a changed entry, an entry built on one through
// `like`, or one whose image changed. It lists what a person must look at (images, measurements).
#include <filesystem>
#include <string>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/curation/check.hpp"
#include "sandpaper/curation/progress.hpp"

namespace sandpaper::curation {

struct ReviewOptions {
  std::filesystem::path library_dir;       // a folder inside a git work tree
  std::filesystem::path calibration_dir;   // empty: calibration::default_calibration_dir()
  std::vector<std::string> devices;        // empty: every device of the calibration
  std::string base = "HEAD";               // the commit to compare with (a branch, tag or hash)
};

struct ReviewResult {
  std::string error;                        // git could not answer (not a work tree, unknown base), in words
  std::vector<std::string> changed_files;   // relative to the library, sorted
  std::vector<std::string> entries;         // the entries the change touches, sorted
  compiler::Diagnostics failing;            // errors and new, unaccepted warnings on those entries
  compiler::Diagnostics accepted;           // warnings those entries accept (shown, not failing)
  std::size_t old_warnings = 0;             // warnings on those entries that the base had too
  std::vector<std::string> by_hand;         // what a reviewer must look at, one line each
  std::size_t devices = 0;
  bool ok() const { return error.empty() && !failing.has_errors() && failing.all().empty(); }
};

// Throws calibration::CalibrationError for unreadable calibration and std::invalid_argument for an
// unknown device; git's failures are in ReviewResult::error.
ReviewResult review_library(const ReviewOptions& options, Progress& progress);

}  // namespace sandpaper::curation
