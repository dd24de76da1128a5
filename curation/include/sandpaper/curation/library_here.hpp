#pragma once
// The library a curator's command (`library check`, `library review`) means when it is not given
// --library: the library of the folder it runs in, never the one the program was built with
// (docs/LIBRARY.md, "Which library").
#include <filesystem>
#include <optional>

namespace sandpaper::curation {

// From `dir` up, the first folder that holds library.toml; at the top of a git work tree (a folder
// holding .git), its library/ when that holds library.toml. The walk stops at that top: a library
// above the repository is not its library. nullopt: no such folder. `dir` is made absolute.
std::optional<std::filesystem::path> library_around(const std::filesystem::path& dir);

}  // namespace sandpaper::curation
