#pragma once
// The catalog's index page: every entry (name, family, roughness, thumbnail, describes) in a table,
// filtered in the browser by family, roughness range and words (assets/index.js). The entries are
// also embedded as JSON in the page (<script type="application/json" id="catalog-data">), so the
// page works from file:// with no server and no fetch.
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

// The embedded data: {"library": {name, version}, "families": [{id, title, describes, count}],
// "entries": [{name, family, family_title, aliases, describes, roughness|null, max_lateral_force_N,
// licence, deprecated_by, page, thumbnail}]}, families in the manifest's order (then any an entry
// names that the manifest lacks), entries in the order given.
nlohmann::json index_data(const compiler::LibraryManifest& manifest, const std::vector<IndexRow>& rows);
// The page: links to assets/catalog.css and assets/index.js.
std::string index_page_html(const nlohmann::json& data);

}  // namespace sandpaper::catalog
