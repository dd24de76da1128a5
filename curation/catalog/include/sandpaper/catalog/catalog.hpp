#pragma once
// `sandpaper library catalog -o DIR`: compiles every library entry and writes the static web catalog
// (index.html, entries/<name>.html with its picture and force plot, assets/). The catalog is built
// in a temporary folder beside DIR and swapped in only when every entry compiled and every file was
// written, so a failed run leaves the previous catalog as it was. Entries whose inputs (curation's
// entry_input_hashes) did not change since the previous catalog, drawn with the same settings,
// keep their files (hard links into the new folder) and are not compiled again.
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sandpaper/compiler/compiler.hpp"

namespace sandpaper::catalog {

struct CatalogOptions {
  std::filesystem::path output;       // DIR
  std::ostream* progress = nullptr;   // where progress goes (stderr); nullptr: none (--quiet)
  bool progress_is_tty = false;       // a "\r" counter rather than a line every 10 entries
  // Pixels, the longer side of an entry's picture at most: the size the entry page shows it (384
  // CSS px; 512 px made photographs' pictures 200 KB, and the catalog 52 KB an entry).
  int picture_side = 384;
  int thumbnail_side = 128;           // pixels, the index's thumbnails
  double thumbnail_window_m = 0.04;   // every thumbnail shows this square (m) around its patch centre
  // Also each picture as Sandpaper's `.shade` array file (`--arrays`): 147 KB an entry at 384 x
  // 384, most of a catalog's size (at most 50 KB an entry without them).
  bool arrays = false;
  // The library files that changed since the index was built (write_catalog_from_index; as
  // curation::IndexOptions::changed): the index is brought up to date from them alone.
  std::optional<std::vector<std::filesystem::path>> changed = std::nullopt;
};

struct CatalogFailure {
  std::string name;         // the entry
  std::string diagnostics;  // formatted, as `sandpaper compile` prints them
};

struct CatalogReport {
  int entries = 0;                        // pages written (0 when anything failed)
  int rendered = 0, reused = 0;           // of them: compiled and drawn now, or kept from the previous catalog
  bool in_place = false;                  // few entries changed: their files replaced in the catalog itself (catalog.cpp)
  // Entries whose input hashes were compared with the record's: every entry, or after an in-place
  // index update only those it rewrote (CatalogSource::since).
  std::size_t compared = 0;
  // The previous record's hashes read but not all its rows (a damaged inputs.sqlite): every entry
  // was drawn again, as with no record, rather than an index missing the rows it could not read.
  bool record_unreadable = false;
  std::vector<CatalogFailure> failures;   // entries that did not compile; nothing is written then
};

// A file DIR holds when this command wrote it; an existing DIR without it is not replaced.
inline constexpr const char* kCatalogMarker = ".sandpaper-catalog";

// Throws std::invalid_argument when DIR exists and is not a catalog (a non-empty folder without the
// marker, or a file), and std::runtime_error when a file cannot be written or DIR cannot be swapped;
// DIR is unchanged then.
CatalogReport write_catalog(const compiler::Compiler& compiler, const CatalogOptions& options);

// What a catalog is drawn from when the library is not read whole (`library catalog` reads the
// entries and their input hashes off the library's index).
struct CatalogSource {
  compiler::LibraryManifest manifest;                          // the index page's title and families
  std::vector<std::pair<std::string, std::string>> entries;    // (name, input hash; "" = always draw), by name
  // A compiler whose library holds at least these entries, what they are built on and the entries
  // they link to; called once, with the entries to draw (not called when there are none), and once
  // more with every entry if the record turns out damaged (CatalogReport::record_unreadable).
  std::function<const compiler::Compiler&(const std::vector<std::string>& names)> compiler_for;
  // Drawn from a library index: its fingerprint, kept in the record with the rows compared with it.
  std::string index_fingerprint;
  // When set, `entries` lists only the entries whose index rows changed since the index had this
  // fingerprint, and `entry_count` says how many there are in all. If the record was last compared
  // with that index, every other entry is as recorded and only these are compared (a one-entry
  // update then reads nothing that grows with the library but the index page's data file);
  // otherwise, or when one of them is new or gone, every_entry() gives the whole list.
  std::optional<std::string> since;
  std::size_t entry_count = 0;
  std::function<std::vector<std::pair<std::string, std::string>>()> every_entry;
  // In a layered library, the entry of a root below that a shown entry hides ("world:corduroy", or
  // ""), when compiler_for's library holds only part of the path; unset: that library's shadowed_by.
  std::function<std::string(const std::string& name)> hides;
};
CatalogReport write_catalog(const CatalogSource& source, const CatalogOptions& options);

// The catalog of one library folder drawn from its index (curation::build_index brings it up to
// date first, in place when few entries changed): only the entries whose input hash differs from
// the previous catalog's are read and compiled, with what they are built on; no other entry file
// is read. nullopt when that cannot be done (a device other than the index's `sim`, or the index
// does not build, for instance an entry that does not compile): then write_catalog(compiler, ...)
// over the whole library does it and reports every failure. Same files as that, byte for byte.
// Throws std::invalid_argument when options.changed names a file of neither the library nor the calibration.
std::optional<CatalogReport> write_catalog_from_index(const std::filesystem::path& library_dir,
                                                      const std::filesystem::path& calibration_dir, const std::string& device,
                                                      const CatalogOptions& options);

// The catalog of a layered library path (roots front first, at least two) drawn from each root's
// index (brought up to date bottom first when stale): the entries the path shows, each compared by
// curation::layered_inputs, so that an edit in one root draws what it changes over the whole path
// and nothing else, reading only those entries' files and what they reach in every root
// (curation::layered_files_reached). nullopt when that cannot be done (a device other than `sim`, or
// a root's index does not build): then write_catalog(compiler, ...) over the whole path does it and
// reports every failure. Same pages, pictures and index as that, byte for byte.
std::optional<CatalogReport> write_catalog_from_layers(const std::vector<std::filesystem::path>& roots,
                                                       const std::filesystem::path& calibration_dir, const std::string& device,
                                                       const CatalogOptions& options);

}  // namespace sandpaper::catalog
