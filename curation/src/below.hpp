#pragma once
// What one root of a layered library path is built over (internal to sandpaper_curation): the
// roots below it, and their indexes' fingerprints when it was built. A root's index records both
// (meta `below`, `below_fingerprint`); a change below makes it stale, and redoes its entries.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sandpaper/curation/index.hpp"

namespace sandpaper::curation {

// The lower roots' absolute folders, one a line ("" for none): meta `below`.
std::string below_paths(const std::vector<std::filesystem::path>& below);

// "<folder> <fingerprint>" of every lower root's index, one a line: meta `below_fingerprint`.
// nullopt if a lower root's index is missing or not fresh (build the roots bottom first).
std::optional<std::string> below_fingerprint(const std::vector<std::filesystem::path>& below,
                                             const std::filesystem::path& calibration_dir);

// index_state() of the root's own files only: its folder, stamps and calibration.
IndexState root_index_state(const std::filesystem::path& index_path, const std::filesystem::path& library_dir,
                            const std::filesystem::path& calibration_dir);

}  // namespace sandpaper::curation
