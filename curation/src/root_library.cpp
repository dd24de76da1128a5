#include "root_library.hpp"

#include <deque>
#include <memory>
#include <set>

#include "sandpaper/curation/layers.hpp"
#include "sqlite_util.hpp"

namespace sandpaper::curation {

std::optional<compiler::Library> library_for_root(const std::filesystem::path& root, const std::vector<std::filesystem::path>& below) {
  std::optional<LayeredIndex> lower;
  try {
    lower.emplace(below);
  } catch (const IndexError&) {
    return std::nullopt;
  }
  const compiler::Library own(root);
  const std::string& own_id = own.roots().front().id;
  std::vector<std::set<std::string>> files(1 + below.size());
  std::deque<std::string> down;
  for (const auto& e : own.entries()) {
    files[0].insert(e.relative_path);
    down.insert(down.end(), e.likes.begin(), e.likes.end());
  }
  // The path's reference: the first any root declares.
  const auto& ref = own.manifest().reference;
  down.push_back(!ref.empty() || below.empty() ? ref : lower->index(0).meta("library_reference"));
  std::vector<std::unique_ptr<sql::Stmt>> file_of, builds_on;
  for (std::size_t i = 0; i < lower->size(); ++i) {
    file_of.push_back(std::make_unique<sql::Stmt>(lower->index(i).handle(), "SELECT file FROM entries WHERE name = ?"));
    builds_on.push_back(std::make_unique<sql::Stmt>(lower->index(i).handle(), "SELECT target FROM depends WHERE name = ? AND kind = 'entry'"));
  }
  std::set<std::pair<std::size_t, std::string>> seen;
  while (!down.empty()) {
    const auto name = std::move(down.front());
    down.pop_front();
    if (name.empty()) continue;
    // The root's own entries are all read, and their chains are already being followed.
    const auto colon = name.find(':');
    if (colon != std::string::npos ? name.substr(0, colon) == own_id : own.entry(name) != nullptr) continue;
    const auto at = lower->resolve(name);
    if (!at || !seen.insert(*at).second) continue;  // a thesis stimulus, or no such entry (the compiler says so)
    auto& f = *file_of[at->first];
    f.bind(1, at->second);
    if (f.step()) files[at->first + 1].insert(f.text(0));
    f.reset();
    auto& b = *builds_on[at->first];
    b.bind(1, at->second);
    while (b.step()) down.push_back(b.text(0));
    b.reset();
  }
  std::vector<std::filesystem::path> path{root};
  path.insert(path.end(), below.begin(), below.end());
  std::vector<std::vector<std::string>> lists;
  for (const auto& s : files) lists.emplace_back(s.begin(), s.end());
  return compiler::Library(path, lists);
}

}  // namespace sandpaper::curation
