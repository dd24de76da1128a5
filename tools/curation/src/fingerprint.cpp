#include <cstdlib>

#include "sandpaper/curation/index.hpp"
#include "stamps.hpp"

namespace sandpaper::curation {

std::filesystem::path default_index_path(const std::filesystem::path& library_dir) {
  if (const char* env = std::getenv("SANDPAPER_LIBRARY_INDEX"); env && *env) return env;
  return library_dir / ".index" / "library.sqlite";
}

// The same list build_index hashes into the index's `fingerprint`.
std::string library_fingerprint(const std::filesystem::path& library_dir, const std::filesystem::path& calibration_dir) {
  stamps::Tree tree;
  stamps::walk(library_dir, "library", {}, stamps::now_ns(), false, tree);
  stamps::walk(calibration_dir, "calibration", {}, stamps::now_ns(), true, tree);
  std::string all = "sandpaper-library-index/" + std::to_string(kIndexSchemaVersion);
  for (const auto& f : tree.files) all += "\n" + f.path + " " + f.hash;
  return stamps::fnv_hex(all);
}

}  // namespace sandpaper::curation
