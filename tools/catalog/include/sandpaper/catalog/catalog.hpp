#pragma once
// `sandpaper library catalog -o DIR`: compiles every library entry and writes the static web catalog
// (index.html, entries/<name>.html with its picture and force plot, assets/). The catalog is built
// in a temporary folder beside DIR and swapped in only when every entry compiled and every file was
// written, so a failed run leaves the previous catalog as it was. Entries whose inputs (curation's
// entry_input_hashes) did not change since the previous catalog, drawn with the same settings,
// keep their files (hard links into the new folder) and are not compiled again.
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "sandpaper/compiler/compiler.hpp"

namespace sandpaper::catalog {

struct CatalogOptions {
  std::filesystem::path output;       // DIR
  std::ostream* progress = nullptr;   // where progress goes (stderr); nullptr: none (--quiet)
  bool progress_is_tty = false;       // a "\r" counter rather than a line every 10 entries
  int picture_side = 512;             // pixels, the longer side of an entry's picture at most
  int thumbnail_side = 128;           // pixels, the index's thumbnails
  double thumbnail_window_m = 0.04;   // every thumbnail shows this square (m) around its patch centre
  // Also each picture as Sandpaper's `.shade` array file (`--arrays`): 262 KB an entry at 512 x
  // 512, most of a catalog's size (issue 18: at most 50 KB an entry without them).
  bool arrays = false;
};

struct CatalogFailure {
  std::string name;         // the entry
  std::string diagnostics;  // formatted, as `sandpaper compile` prints them
};

struct CatalogReport {
  int entries = 0;                        // pages written (0 when anything failed)
  int rendered = 0, reused = 0;           // of them: compiled and drawn now, or kept from the previous catalog
  std::vector<CatalogFailure> failures;   // entries that did not compile; nothing is written then
};

// A file DIR holds when this command wrote it; an existing DIR without it is not replaced.
inline constexpr const char* kCatalogMarker = ".sandpaper-catalog";

// Throws std::invalid_argument when DIR exists and is not a catalog (a non-empty folder without the
// marker, or a file), and std::runtime_error when a file cannot be written or DIR cannot be swapped;
// DIR is unchanged then.
CatalogReport write_catalog(const compiler::Compiler& compiler, const CatalogOptions& options);

}  // namespace sandpaper::catalog
