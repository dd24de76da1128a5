#pragma once
// The studio's library browser (docs/STUDIO.md): search the library through its SQLite index (the
// same `sandpaper library search` reads), an entry's numbers and picture, and its text to read.
// The index of the compiler's front library root is built, or brought up to date, on first use.
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/compiler.hpp"

namespace sandpaper::studio {

class LibraryBrowser {
 public:
  // `compiler` must outlive the browser; pictures are written into `picture_dir`.
  LibraryBrowser(const compiler::Compiler& compiler, std::filesystem::path picture_dir);

  // {"entries": [{"name", "family", "describes", "aliases", "compiled_roughness",
  // "compiled_max_lateral_force_N", "period_mm" (null without one), "file"}], "index": "fresh"|"built"}:
  // up to 30 entries matching `words` (names, aliases, descriptions; the last word also as a prefix),
  // or all by roughness without words. RequestError 503 when the index cannot be built (the message
  // says why: `sandpaper library check` says more).
  nlohmann::json search(const std::string& words);
  // One entry by name or alias: the search's fields plus "text" (its file, to read) and
  // "picture" (true when picture() has one). RequestError 404 for no such entry.
  nlohmann::json entry(const std::string& name);
  // The entry's shaded height field as a PNG file (the catalog's renderer), drawn on first request;
  // nullopt for an entry with no surface to draw or no such entry.
  std::optional<std::filesystem::path> picture(const std::string& name);

 private:
  std::filesystem::path ensure_index();  // under mutex_

  const compiler::Compiler& compiler_;
  std::filesystem::path picture_dir_;
  std::mutex mutex_;
  std::string index_state_;  // "" until first built or found fresh
};

}  // namespace sandpaper::studio
