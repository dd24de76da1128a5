#pragma once
// The part of a layered path that indexing one root reads (internal to sandpaper_curation).
#include <filesystem>
#include <optional>
#include <vector>

#include "sandpaper/compiler/library.hpp"

namespace sandpaper::curation {

// The library [root] + below with every entry file of `root`, and of the roots below only the files
// its entries reach: down their `like` chains (each name resolved front first, `root` before the
// roots below), and the reference entry, found in the lower roots' indexes rather than by reading
// those roots (at 100,000 entries below, reading them was most of indexing a lab's root). nullopt
// when a lower root's index cannot be read: then the caller reads the whole path.
std::optional<compiler::Library> library_for_root(const std::filesystem::path& root, const std::vector<std::filesystem::path>& below);

}  // namespace sandpaper::curation
