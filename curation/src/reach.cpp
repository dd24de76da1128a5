#include "reach.hpp"

#include <deque>

#include "sqlite_util.hpp"

namespace sandpaper::curation {

std::set<std::string> files_reached(sqlite3* db, const std::vector<std::string>& names, const std::vector<std::string>& extra_names,
                                    const std::function<std::optional<ReachedEntry>(const std::string&)>& overlay,
                                    const std::function<bool(const std::string&)>& stale) {
  sql::Stmt by_name(db, "SELECT name, file FROM entries WHERE name = ?");
  sql::Stmt by_alias(db, "SELECT e.name, e.file FROM aliases a JOIN entries e ON e.name = a.name WHERE a.alias = ?");
  sql::Stmt builds_on(db, "SELECT target FROM depends WHERE name = ? AND kind = 'entry'");
  // (name, file) of a name or alias in the rows, if its row is current.
  const auto lookup = [&](const std::string& n) -> std::optional<std::pair<std::string, std::string>> {
    for (auto* s : {&by_name, &by_alias}) {
      s->bind(1, n);
      std::optional<std::pair<std::string, std::string>> hit;
      if (s->step()) hit = std::make_pair(s->text(0), s->text(1));
      s->reset();
      if (hit) return stale(hit->second) ? std::nullopt : hit;
    }
    return std::nullopt;
  };
  std::set<std::string> files, seen;
  for (const auto& n : extra_names) {
    if (const auto o = overlay(n)) files.insert(o->file);
    else if (const auto hit = lookup(n)) files.insert(hit->second);
  }
  std::deque<std::string> down(names.begin(), names.end());
  while (!down.empty()) {
    const auto n = down.front();
    down.pop_front();
    if (!seen.insert(n).second) continue;
    if (const auto o = overlay(n)) {
      files.insert(o->file);
      down.insert(down.end(), o->builds_on.begin(), o->builds_on.end());
      continue;
    }
    const auto hit = lookup(n);
    if (!hit) continue;  // a thesis stimulus, or a name no entry has
    files.insert(hit->second);
    builds_on.bind(1, hit->first);
    while (builds_on.step()) down.push_back(builds_on.text(0));
    builds_on.reset();
  }
  return files;
}

}  // namespace sandpaper::curation
