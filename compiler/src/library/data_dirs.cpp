// Where the shipped data is looked for when no directory is given (data_dirs.hpp). This file alone
// differs between the build tree (built-in default: the source tree's library/ and calibration/)
// and an installed package (<prefix>/share/sandpaper/..., and the same path relative to the
// installed programs so a moved prefix still works). compiler/CMakeLists.txt builds it twice.
#include "sandpaper/compiler/data_dirs.hpp"

#include <mutex>
#include <cstdlib>
#include <system_error>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/library.hpp"

#if !defined(SANDPAPER_DEFAULT_DATA_DIR_LIBRARY) || !defined(SANDPAPER_DEFAULT_DATA_DIR_CALIBRATION)
#error "data_dirs.cpp is built by compiler/CMakeLists.txt with SANDPAPER_DEFAULT_DATA_DIR_LIBRARY and _CALIBRATION"
#endif

namespace sandpaper::compiler {
namespace {

// Set from the application's static initialisers (set_package_data_dir_nonrt), which may run before
// this file's: a function-local static is built on first use, whichever file uses it first.
struct PackageDataDir {
  std::mutex mutex;
  std::filesystem::path dir;  // empty: none registered, or not an absolute path
};
PackageDataDir& package() {
  static PackageDataDir p;
  return p;
}

std::filesystem::path registered_package_data_dir() {
  auto& p = package();
  std::lock_guard lock(p.mutex);
  return p.dir;
}

const char* env(const char* name) {
  const char* v = std::getenv(name);
  return v && *v ? v : nullptr;
}

#ifdef SANDPAPER_BIN_TO_DATA_DIR
// Installed programs (the CLI, the player) find the data from where they are, so an install moved
// to another prefix, or unpacked from a package elsewhere, needs no environment.
std::filesystem::path beside_program() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec || exe.empty()) return {};
  const auto dir = (exe.parent_path() / SANDPAPER_BIN_TO_DATA_DIR).lexically_normal();
  return std::filesystem::is_directory(dir, ec) ? dir : std::filesystem::path{};
}
#endif

DataDirChoice find(const char* specific_env, const char* sub, const char* built_in) {
  if (const char* v = env(specific_env)) return {v, std::string("$") + specific_env};
  if (const char* v = env("SANDPAPER_DATA_DIR")) return {std::filesystem::path(v) / sub, "$SANDPAPER_DATA_DIR"};
  if (auto dir = registered_package_data_dir(); !dir.empty())
    return {dir / sub, "the package this program was built against"};
#ifdef SANDPAPER_BIN_TO_DATA_DIR
  if (auto dir = beside_program(); !dir.empty()) return {dir / sub, "beside the program"};
#endif
  return {built_in, "the built-in default"};
}

}  // namespace

DataDirChoice find_library_dir() {
  return find("SANDPAPER_LIBRARY", "library", SANDPAPER_DEFAULT_DATA_DIR_LIBRARY);
}
DataDirChoice find_calibration_dir() {
  return find("SANDPAPER_CALIBRATION", "calibration", SANDPAPER_DEFAULT_DATA_DIR_CALIBRATION);
}

void set_package_data_dir_nonrt(const char* header_file, const char* header_dir_to_data) noexcept {
  if (!header_file || !header_dir_to_data) return;
  try {
    const std::filesystem::path header(header_file);
    // A relative __FILE__ (an -I relative to the application's build folder) says nothing at run time.
    if (!header.is_absolute()) return;
    auto dir = (header.parent_path() / header_dir_to_data).lexically_normal();
    auto& p = package();
    std::lock_guard lock(p.mutex);
    p.dir = std::move(dir);
  } catch (...) {  // before main: out of memory here leaves the other defaults
  }
}

std::string missing_data_dirs_message(const std::vector<std::pair<std::string, DataDirChoice>>& dirs) {
  std::string missing;
  for (const auto& [what, choice] : dirs) {
    std::error_code ec;
    if (std::filesystem::is_directory(choice.dir, ec)) continue;
    missing += missing.empty() ? "" : "; ";
    missing += "no " + what + " directory at " + choice.dir.string() + " (chosen by " + choice.chosen_by + ")";
  }
  if (missing.empty()) return {};
  return "Sandpaper's data was not found: " + missing +
         ". Set SANDPAPER_DATA_DIR to the folder holding library/ and calibration/ (an installed package's "
         "share/sandpaper), or SANDPAPER_LIBRARY and SANDPAPER_CALIBRATION, or pass the directories";
}

std::filesystem::path default_library_dir() { return find_library_dir().dir; }

}  // namespace sandpaper::compiler

namespace sandpaper::calibration {
std::filesystem::path default_calibration_dir() { return compiler::find_calibration_dir().dir; }
}  // namespace sandpaper::calibration
