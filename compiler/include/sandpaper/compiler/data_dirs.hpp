// Where the shipped data (the library and the calibration) is found when no directory is given,
// and what chose each directory, so that an error can say how to point elsewhere. docs/API.md,
// "Data directories". Everything here is non-real-time (it reads the environment and the disk).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace sandpaper::compiler {

// A data directory and what chose it, for messages: "$SANDPAPER_LIBRARY", "$SANDPAPER_DATA_DIR",
// "the package this program was built against", "beside the program", "the built-in default".
struct DataDirChoice {
  std::filesystem::path dir;
  std::string chosen_by;
};

// The first that applies: $SANDPAPER_LIBRARY (resp. $SANDPAPER_CALIBRATION); $SANDPAPER_DATA_DIR/library
// (resp. /calibration); the package data directory the application was built against
// (set_package_data_dir_nonrt); <program's folder>/../share/sandpaper if it exists (installed
// programs, wherever the prefix was moved); the built-in default (the source tree in a build tree,
// the configured install prefix in an installed package). Never throws; the directory may not exist.
DataDirChoice find_library_dir();
DataDirChoice find_calibration_dir();

// Records where an installed package's data lies: `header_file` is the __FILE__ of its installed
// sandpaper/package_location.h and `header_dir_to_data` the path from that header's folder to
// <prefix>/share/sandpaper, so the data is found wherever the package was moved. Applications call
// it before main by including sandpaper/sandpaper.hpp or sandpaper.h from an install (the header
// exists only there). Both strings must outlive the program (string literals). Thread-safe.
void set_package_data_dir_nonrt(const char* header_file, const char* header_dir_to_data) noexcept;

// One message for every missing directory at once, each with what chose it, and how to fix it.
// `missing`: (what, choice) pairs, e.g. {"library", find_library_dir()}. Empty when none is missing.
std::string missing_data_dirs_message(const std::vector<std::pair<std::string, DataDirChoice>>& dirs);

}  // namespace sandpaper::compiler
