// path_affected (affected.hpp).
#include "affected.hpp"

#include <deque>
#include <unordered_map>
#include <unordered_set>

#include "sqlite_util.hpp"

namespace sandpaper::curation {

namespace {

// The entries of root `layer` whose compiled form or page could differ between the root's own
// index (the root over those below it) and the whole path: those built, through `like` or the
// reference, on a name in `seeds` (a name a root in front defines, or an affected entry of a root
// below), on the thesis' readings when `thesis` (a root in front has them), or that link to such a
// name as their replacement; and then everything built on those. Over-counts rather than misses.
std::set<std::string> affected_in(const Index& idx, const std::string& id, std::deque<std::string> seeds, bool thesis) {
  sqlite3* db = idx.handle();
  sql::Stmt built_on(db, "SELECT name FROM depends WHERE kind = 'entry' AND target = ?");
  sql::Stmt reads(db, "SELECT name FROM depends WHERE kind = 'file' AND target = 'library/thesis/version1.toml'");
  sql::Stmt aliases(db, "SELECT alias FROM aliases WHERE name = ?");
  std::unordered_map<std::string, std::vector<std::string>> replaced_by;  // deprecated_by -> entries
  {
    sql::Stmt d(db, "SELECT name, deprecated_by FROM entries WHERE deprecated_by <> ''");
    while (d.step()) replaced_by[d.text(1)].push_back(d.text(0));
  }
  std::set<std::string> out;
  std::deque<std::string> found;
  if (thesis)
    while (reads.step()) found.push_back(reads.text(0));
  std::unordered_set<std::string> seen;
  while (!seeds.empty() || !found.empty()) {
    while (!found.empty()) {
      const auto name = std::move(found.front());
      found.pop_front();
      if (!out.insert(name).second) continue;
      // What is built on it names it by its name or an alias, plain or as ID:NAME.
      seeds.push_back(name);
      seeds.push_back(id + ":" + name);
      aliases.bind(1, name);
      while (aliases.step()) seeds.push_back(aliases.text(0)), seeds.push_back(id + ":" + aliases.text(0));
      aliases.reset();
    }
    while (!seeds.empty()) {
      const auto target = std::move(seeds.front());
      seeds.pop_front();
      if (!seen.insert(target).second) continue;
      built_on.bind(1, target);
      while (built_on.step()) found.push_back(built_on.text(0));
      built_on.reset();
      if (const auto it = replaced_by.find(target); it != replaced_by.end())
        found.insert(found.end(), it->second.begin(), it->second.end());
    }
  }
  return out;
}

}  // namespace

std::size_t thesis_root(const std::vector<std::filesystem::path>& roots) {
  std::error_code ec;
  for (std::size_t i = 0; i < roots.size(); ++i)
    if (std::filesystem::is_regular_file(roots[i] / "thesis" / "version1.toml", ec)) return i;
  return roots.size();
}

std::vector<std::set<std::string>> path_affected(const LayeredIndex& idx, const std::vector<std::filesystem::path>& roots) {
  const std::size_t n = idx.size();
  const std::size_t thesis = thesis_root(roots);
  const std::string reference = n ? idx.index(0).meta("library_reference") : std::string();
  // Bottom first: an entry built on an affected entry below is affected.
  std::vector<std::set<std::string>> affected(n);
  std::vector<std::string> affected_names;  // names and aliases of affected entries, plain and ID:NAME
  for (std::size_t layer = n; layer-- > 0;) {
    std::deque<std::string> seeds(affected_names.begin(), affected_names.end());
    for (std::size_t front = 0; front < layer; ++front)
      for (auto& name : idx.index(front).names_and_aliases()) seeds.push_back(std::move(name));
    // The reference this root's own index compiled bare descriptions on, if the path's differs.
    if (const auto own = idx.index(layer).meta("library_reference"); !own.empty() && own != reference) seeds.push_back(own);
    affected[layer] = affected_in(idx.index(layer), idx.id(layer), std::move(seeds), thesis < layer);
    for (const auto& name : affected[layer]) {
      affected_names.push_back(name);
      affected_names.push_back(idx.id(layer) + ":" + name);
      if (const auto e = idx.index(layer).entry(name))
        for (const auto& a : e->aliases) affected_names.push_back(a), affected_names.push_back(idx.id(layer) + ":" + a);
    }
  }
  return affected;
}

}  // namespace sandpaper::curation
