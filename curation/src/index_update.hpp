#pragma once
// The in-place update of an index when few entries changed (internal to sandpaper_curation;
// index_update.cpp says how).
#include <cstdint>
#include <filesystem>
#include <optional>

#include "sandpaper/curation/index.hpp"
#include "stamps.hpp"

namespace sandpaper::curation {

// IndexOptions::changed as tagged paths ("library/textiles/corduroy.hmat"), hidden ones left out;
// sets `error` (and returns nothing) for a path in neither folder.
std::vector<stamps::Listed> tag_changed(const std::vector<std::filesystem::path>& changed, const std::filesystem::path& lib_dir,
                                        const std::filesystem::path& cal_dir, std::string& error);

// Updates the index at `index_path` in place, in one transaction, if at most options.batch
// entries need compiling and nothing needs the whole library; nullopt: nothing was written, and
// the batched build (build_index) is to run. Throws sql::Error for SQLite failures after writing began.
std::optional<IndexBuildResult> update_in_place(const IndexOptions& options, const std::filesystem::path& lib_dir,
                                                const std::filesystem::path& cal_dir, const std::filesystem::path& index_path,
                                                std::int64_t start_ns, Progress& progress);

}  // namespace sandpaper::curation
