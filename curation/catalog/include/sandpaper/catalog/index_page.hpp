#pragma once
// The catalog's index page: the entries (name, family, roughness, thumbnail, describes) a page of
// rows at a time, filtered in the browser by family, roughness range, licence, source kind and
// words, ordered by name or roughness, some ticked to compare side by side (assets/index.js).
// The page itself holds no entry: the entries are in compact data files beside it (kIndexDataFile
// and its parts), loaded by plain <script src>, so that the page works from file:// with no server
// (browsers refuse fetch() of local files) and still opens fast with 100,000 entries.
#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/library.hpp"

namespace sandpaper::catalog {

struct IndexRow {
  std::string name, family, describes, licence, deprecated_by;
  std::vector<std::string> aliases;
  std::optional<double> roughness;  // compiled ratio-scale roughness; none without a texture
  double max_lateral_force_N = 0;   // the texture's compiled maximum lateral force, N; 0 without one
  double period_m = 0;              // the texture's spatial period, m (curation::Percepts); 0 when it has none
  std::string kind;                 // "<texture kind>|<term kinds>" ("grating|grating+spring"), as `near` classes them
  unsigned source_kinds = 0;        // bit k set: a `source` note of compiler::SourceKind k in the entry's own file
  std::string root;                 // in a layered library, the id of the root the entry is from; else ""
  std::string page;                 // "entries/corduroy.html"
  std::string thumbnail;            // "entries/corduroy-thumb.png", or empty without a picture
};

// The index's data: a small head file beside index.html (the library, the families with their
// counts, and each part's first and last name), and the rows themselves in parts of kIndexPartRows
// rows, kIndexPartsFolder/part-NNNNN.js, so that a one-entry update rewrites one part (about 100 KB)
// and not the whole index (4.7 MB at 100,000 entries).
inline constexpr const char* kIndexDataFile = "catalog-data.js";
inline constexpr const char* kIndexPartsFolder = "catalog-data";
inline constexpr std::size_t kIndexPartRows = 2048;
// "catalog-data/part-00007.js" for part 7.
std::string index_part_file(std::size_t part);

// Every row as JSON: {"library": {name, version}, "families": [{id, title, describes, count, stimulus (if true)}],
// "entries": [{name, family, family_title, aliases, describes, roughness|null, max_lateral_force_N,
// period_m, kind, source_kinds, root, licence, deprecated_by, page, thumbnail}]}, families in the manifest's order (then any an entry
// names that the manifest lacks), entries in the order given. What the index's files are made from.
nlohmann::json index_data(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows);

// The index's files, by path relative to the catalog folder: "index.html", kIndexDataFile and
// index_part_file(k) for every part. All ASCII, in this format (format 3):
// - index.html: the filters (the family select lists the families with their counts), the count
//   line, the pagers and an empty table that assets/index.js fills; a <noscript> note for browsers
//   without JavaScript. It loads kIndexDataFile, then every part, by plain <script src> (browsers
//   refuse fetch() of a file:// URL), then assets/index.js.
// - kIndexDataFile: `window.sandpaperCatalog = JSON.parse('...');` with
//   {"entries": N, "families": [{"count", "id", "stimulus" (true, only for a stimulus set), "title"}], "format": 3, "library": {name, version},
//    "part_rows": kIndexPartRows, "parts": [{"families": [rows of the part in each family], "first": name,
//    "last": name, "rows": n, "unfiled": rows of the part without a family}],
//    "sorted": whether the names are in strictly increasing byte order, "unfiled": entries without a family}
//   The family counts and "unfiled" are the sums over the parts (a patch recounts the parts it rewrites).
// - each part: `(window.sandpaperCatalogParts = window.sandpaperCatalogParts || []).push(JSON.parse('...'));`
//   with the rows part_rows * k onwards, a column per field: {"aliases": {"<row in part>": [...]},
//   "deprecated_by": {"<row in part>": name}, "describes": [...], "family": [index into families, or
//   -1], "force_N": [maximum lateral force, N, 6 significant digits; 0 without a texture], "format": 3,
//   "kind": ["<texture kind>|<term kinds>"], "licence": [SPDX expression as written], "name": [...],
//   "no_thumbnail": [row in part, ...], "part": k, "period_m": [m, 6 significant digits; 0: none],
//   "root": {"<row in part>": root id}, "roughness": [number|null, 6 significant digits],
//   "sources": [IndexRow::source_kinds]}.
// Paths are not stored: an entry's page is entries/<name>.html and its thumbnail
// entries/<name>-thumb.png. Throws std::invalid_argument for a row whose page or thumbnail is
// elsewhere, which the page could not find.
using IndexFiles = std::map<std::string, std::string>;
IndexFiles index_files(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows);
// The same files for index_data's JSON.
IndexFiles index_files(const nlohmann::json& data);

// The index's files after `changed` rows replace theirs, each at its name's place: the head file,
// the page, and the parts that hold those rows (the others are as they were), read through `read`
// (a path relative to the catalog folder -> its text, nullopt if missing or too large). The same
// text as index_files gives for the whole list with those rows changed, without reading the other
// parts when the names are sorted. nullopt when it cannot be done so (files not of this format, a
// name they lack, a family the list lacks or would lose, or the manifest's library or families
// differ): then every file is written whole.
using ReadIndexFile = std::function<std::optional<std::string>(const std::string& relative_path)>;
std::optional<IndexFiles> patch_index(const ReadIndexFile& read, const compiler::LibraryManifest& manifest,
                                      const std::vector<IndexRow>& changed);

}  // namespace sandpaper::catalog
