#pragma once
// What every `sandpaper library` subcommand shares (cmd_library*.cpp): the library path with each
// root's index, kept fresh before a query answers, and how entries are printed.
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cmd_library.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/layers.hpp"

namespace sandpaper::cli::library_cmd {

namespace cur = sandpaper::curation;

// "1 entry", "2 entries".
std::string entries_text(std::size_t n);
// `v` to `digits` significant digits.
std::string num(double v, int digits = 3);
// `s` padded with spaces to `w` characters.
std::string pad(const std::string& s, std::size_t w);
// --library and --calibration (and --index when `index`); `here`: the default library is the working
// directory's (check, review), not the shipped one.
void add_paths(CLI::App* sub, LibraryCommandOptions& o, bool index, bool here = false);

struct Paths {
  std::filesystem::path library, calibration, index;  // library: the front root; index: its index
  std::vector<std::filesystem::path> roots;           // the library path, front first (one folder unless layered)
  std::vector<std::filesystem::path> indexes;         // each root's index, parallel to roots
  bool layered() const { return roots.size() > 1; }
  std::vector<std::filesystem::path> below(std::size_t i) const {
    return {roots.begin() + static_cast<std::ptrdiff_t>(i) + 1, roots.end()};
  }
};
// The subcommand's folders from its own options, else its parent's, else the defaults; throws
// std::invalid_argument for a missing folder or --index with a layered path.
Paths paths_of(const CommonOptions& common, const LibraryCommandOptions& o);
// Prints why an index was not written; the exit code (1: the library has errors, 2: otherwise).
int print_build_failure(const cur::IndexBuildResult& r, const char* who);
// Builds each root's index that is missing or stale, the bottom root first (a root's index is
// built over those below it); returns the exit code of a failed build, or 0 (also when a rebuild
// failed but the previous index of that root can still answer).
int ensure_index(const Paths& p, bool quiet, const char* who);
nlohmann::json entry_json(const cur::IndexedEntry& e, bool layered);
// The files of `entries` ((root, name)) saved in place since their root's index was built, by root:
// an edit the cheap staleness check (index_state) does not see, in a folder whose time it keeps.
std::map<std::size_t, std::vector<std::filesystem::path>> edited_since_index(
    const Paths& p, const cur::LayeredIndex& layers, const std::vector<std::pair<std::size_t, std::string>>& entries);
// Brings the indexes up to date after those edits, saying so; queries then answer with what the
// files say now, not with the old values.
int refresh_edited(const Paths& p, const std::map<std::size_t, std::vector<std::filesystem::path>>& edited, bool quiet,
                   const char* who);
// Over a layered path, the entries of lower roots that the roots in front change are compiled over
// the path, as explain compiles them; one that does not compile there is answered from its root's
// index, with the compiler's errors on stderr.
void see_through(cur::LayeredIndex& idx, const Paths& p, const char* who);
// "world:corduroy" for an entry of a layered path, else its name.
std::string shown_name(const cur::IndexedEntry& e, bool layered);
// Says that `name` is neither an entry nor an alias, with the closest one; returns 1.
int unknown_entry(const cur::LayeredIndex& idx, const std::string& name, const char* who);

// The subcommands (cmd_library.cpp: check, review, index; cmd_library_query.cpp: search, show, near).
int run_check(const Paths& p, const LibraryCommandOptions& o);
int run_review(const Paths& p, const LibraryCommandOptions& o);
int run_index(const Paths& p, const LibraryCommandOptions& o);
int run_search(const Paths& p, const LibraryCommandOptions& o);
int run_show(const Paths& p, const LibraryCommandOptions& o);
int run_near(const Paths& p, const LibraryCommandOptions& o);

}  // namespace sandpaper::cli::library_cmd
