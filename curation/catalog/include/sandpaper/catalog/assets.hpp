#pragma once
// The catalog's static files (assets/catalog.css, assets/index.js), compiled into the program so the
// catalog can be written from an installed binary; generated from curation/catalog/assets/ at build time.
#include <string_view>
#include <vector>

namespace sandpaper::catalog {

struct Asset {
  std::string_view name;  // "catalog.css", written to DIR/assets/<name>
  std::string_view text;
};
const std::vector<Asset>& assets();

}  // namespace sandpaper::catalog
