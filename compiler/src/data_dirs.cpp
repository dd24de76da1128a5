// Where the shipped data is looked for when no directory is given: the two default-directory
// functions, in a file of their own so that only it differs between the build tree (the source
// tree's library/ and calibration/) and an installed package (<datadir>/sandpaper/...). It is
// compiled twice with different SANDPAPER_DEFAULT_*_DIR (compiler/CMakeLists.txt); nothing else is.
#include <cstdlib>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/library.hpp"

#if !defined(SANDPAPER_DEFAULT_LIBRARY_DIR) || !defined(SANDPAPER_DEFAULT_CALIBRATION_DIR)
#error "data_dirs.cpp is built by compiler/CMakeLists.txt with SANDPAPER_DEFAULT_LIBRARY_DIR and SANDPAPER_DEFAULT_CALIBRATION_DIR"
#endif

namespace sandpaper::compiler {
std::filesystem::path default_library_dir() {
  if (const char* env = std::getenv("SANDPAPER_LIBRARY"); env && *env) return env;
  return SANDPAPER_DEFAULT_LIBRARY_DIR;
}
}  // namespace sandpaper::compiler

namespace sandpaper::calibration {
std::filesystem::path default_calibration_dir() {
  if (const char* env = std::getenv("SANDPAPER_CALIBRATION"); env && *env) return env;
  return SANDPAPER_DEFAULT_CALIBRATION_DIR;
}
}  // namespace sandpaper::calibration
