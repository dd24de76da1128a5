#pragma once
// Which entries of a layered path the roots in front change (internal to sandpaper_curation): the
// catalog redraws them, and queries compile them over the whole path (path_view.cpp).
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "sandpaper/curation/layers.hpp"

namespace sandpaper::curation {

// The first root of the path with the thesis' readings, as compiler::Library::thesis_directory()
// looks for them; roots.size() if none.
std::size_t thesis_root(const std::vector<std::filesystem::path>& roots);

// For each root (front first), its entries whose compiled form or page could differ between the
// root's own index (the root over those below it) and the whole path: those built, through `like`
// or the reference, on a name a root in front defines or on such an entry below, on the thesis'
// readings when a root in front has them, or that link to such a name as their replacement; and
// everything built on those. Over-counts rather than misses; the front root's set is empty. Reads
// the indexes' `depends`, `aliases` and `entries` rows only.
std::vector<std::set<std::string>> path_affected(const LayeredIndex& idx, const std::vector<std::filesystem::path>& roots);

}  // namespace sandpaper::curation
