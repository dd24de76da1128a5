#pragma once
// What each library entry's compiled form depends on, as one hash per entry (docs/LIBRARY.md,
// "Incremental builds"): `library index` and `library catalog` redo only entries whose hash changed.
#include <filesystem>
#include <map>
#include <string>

#include "sandpaper/compiler/compiler.hpp"

namespace sandpaper::curation {

// Entry name -> hex hash of its file, its images, its `like` chain, the reference entry for a bare
// perceptual description, library.toml, the calibration folder, the compiler version and device.
// Reads every file of the library (one root) and of `calibration_dir` (empty: the default).
// A layered library gives an empty map: its entries are not hashed yet.
std::map<std::string, std::string> entry_input_hashes(const compiler::Compiler& compiler, const std::filesystem::path& calibration_dir);

}  // namespace sandpaper::curation
