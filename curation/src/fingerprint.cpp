#include <cstdlib>

#include "sandpaper/curation/index.hpp"
#include "stamps.hpp"

namespace sandpaper::curation {

std::filesystem::path default_index_path(const std::filesystem::path& library_dir) {
  if (const char* env = std::getenv("SANDPAPER_LIBRARY_INDEX"); env && *env) return env;
  return library_dir / ".index" / "library.sqlite";
}

// What build_index records as the index's `fingerprint`, from every file's bytes.
std::string library_fingerprint(const std::filesystem::path& library_dir, const std::filesystem::path& calibration_dir) {
  stamps::Tree tree;
  stamps::walk(library_dir, "library", {}, stamps::now_ns(), false, tree);
  stamps::walk(calibration_dir, "calibration", {}, stamps::now_ns(), true, tree);
  return stamps::fingerprint(tree.files);
}

}  // namespace sandpaper::curation
