#pragma once
// Which of a library's files came first, by git's history (internal to sandpaper_curation):
// `library check` decides which of two entries with one name is established and which is the
// newcomer, when the library's index does not say.
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace sandpaper::curation {

// For each of `files` (relative to `dir`, a folder in a git work tree) that a commit reachable from
// HEAD added: the rank of the first commit that added it, 0 for the oldest, parents before children
// (renames count as additions). Files git never committed, and every file when `dir` is not in a
// work tree or git cannot be run, are left out.
std::map<std::string, std::size_t> first_added(const std::filesystem::path& dir, const std::vector<std::string>& files);

}  // namespace sandpaper::curation
