#pragma once
// The part of a library some entries need, read off an index without reading the library
// (internal to sandpaper_curation; used by the in-place update and by Index::files_reached).
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

struct sqlite3;

namespace sandpaper::curation {

// An entry as known outside the index's rows (parsed just now): its file and the names it is built on.
struct ReachedEntry {
  std::string file;                     // relative to the library
  std::vector<std::string> builds_on;   // `like` targets as written, the reference
};

// Entry files (relative to the library) of `names` and of every entry they are built on (table
// `depends`, kind 'entry'), plus `extra_names` themselves without what they are built on (the
// entries a page links to). Each name is resolved as the library resolves it: an entry's name
// before another's alias. `overlay` answers first; rows whose file `stale` says is out of date
// are not followed (their entry is gone or answered by the overlay).
std::set<std::string> files_reached(sqlite3* db, const std::vector<std::string>& names, const std::vector<std::string>& extra_names,
                                    const std::function<std::optional<ReachedEntry>(const std::string&)>& overlay,
                                    const std::function<bool(const std::string&)>& stale);

}  // namespace sandpaper::curation
