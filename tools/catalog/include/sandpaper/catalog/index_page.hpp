#pragma once
// The catalog's index page: the entries (name, family, roughness, thumbnail, describes) a page of
// rows at a time, filtered in the browser by family, roughness range and words (assets/index.js).
// The page itself holds no entry: the entries are in a separate, compact data file beside it
// (kIndexDataFile), loaded by a plain <script src>, so that the page works from file:// with no
// server (browsers refuse fetch() of local files) and still opens fast with 100,000 entries.
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
  double max_lateral_force_N = 0;
  std::string page;                 // "entries/corduroy.html"
  std::string thumbnail;            // "entries/corduroy-thumb.png", or empty without a picture
};

// The index's data file, written beside index.html.
inline constexpr const char* kIndexDataFile = "catalog-data.js";

// Every row as JSON: {"library": {name, version}, "families": [{id, title, describes, count}],
// "entries": [{name, family, family_title, aliases, describes, roughness|null, max_lateral_force_N,
// licence, deprecated_by, page, thumbnail}]}, families in the manifest's order (then any an entry
// names that the manifest lacks), entries in the order given.
nlohmann::json index_data(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows);

// The page: the filters (the family select lists index_data's families with their counts), the count
// line, the pagers and an empty table that assets/index.js fills from kIndexDataFile; a <noscript>
// note for browsers without JavaScript. Links to assets/catalog.css and assets/index.js.
std::string index_page_html(const nlohmann::json& data);
// The same page for index_data(manifest, rows), without building that JSON.
std::string index_page_html(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows);

// The text of kIndexDataFile for index_data's JSON: one statement, in ASCII,
// `window.sandpaperCatalog = JSON.parse('...');` with the JSON below as the string literal. Only what
// the index shows or filters by, a column per field rather than an object per entry, so that 100,000
// entries are a few megabytes:
//   {"format": 1, "library": {name, version}, "families": [{id, title}],
//    "name": [...], "family": [index into families, or -1], "roughness": [number|null, 6 significant
//    digits], "describes": [...], "aliases": {"<entry index>": [...]} (entries with aliases only),
//    "deprecated_by": {"<entry index>": name}, "no_thumbnail": [entry index, ...]}
// Paths are not stored: the page is entries/<name>.html and the thumbnail entries/<name>-thumb.png, as
// the catalog writes them. Throws std::invalid_argument for an entry whose page or thumbnail is
// elsewhere, which the page could not find.
std::string index_data_script(const nlohmann::json& data);
// The same text for index_data(manifest, rows), written straight from the rows (0.2 s rather than 2 s at 100,000).
std::string index_data_script(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows);

// The data file and the index page after `changed` rows replace theirs in an existing data file's
// text (`script`, index_data_script's), each row at its name's place: the same text as both
// functions give for the whole list with those rows changed, without the other rows. nullopt when
// it cannot be done so (not such a file, a name it lacks, a family its list lacks or would lose,
// or the manifest's families differ): then the whole file is written.
struct PatchedIndex {
  std::string script, page;
};
std::optional<PatchedIndex> patch_index(const std::string& script, const compiler::LibraryManifest& manifest,
                                        const std::vector<IndexRow>& changed);

}  // namespace sandpaper::catalog
