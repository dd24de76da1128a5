// first_added (first_added.hpp).
#include "first_added.hpp"

#include "subprocess.hpp"

namespace sandpaper::curation {

std::map<std::string, std::size_t> first_added(const std::filesystem::path& dir, const std::vector<std::string>& files) {
  std::map<std::string, std::size_t> out;
  if (files.empty()) return out;
  // Oldest first (--reverse of the topological order); each commit is a \1-marked hash, then the
  // paths it added, relative to `dir`, NUL-separated.
  std::vector<std::string> argv{"git",         "-C",           dir.string(), "-c",          "core.quotepath=off",
                                "log",         "--no-renames", "--relative", "--diff-filter=A", "--reverse",
                                "--topo-order", "--format=%x01%H", "--name-only", "-z",          "--"};
  for (const auto& f : files) argv.push_back(":(literal)" + f);
  const auto text = run_capture(argv);
  if (!text) return out;
  std::size_t rank = 0, start = 0;
  bool any_commit = false;
  while (start < text->size()) {
    auto end = text->find('\0', start);
    if (end == std::string::npos) end = text->size();
    std::string token = text->substr(start, end - start);
    start = end + 1;
    if (!token.empty() && token.front() == '\x01') {
      if (any_commit) ++rank;
      any_commit = true;
      continue;
    }
    if (!token.empty() && token.front() == '\n') token.erase(0, 1);
    if (!token.empty()) out.emplace(token, rank);  // emplace keeps the first (oldest) addition
  }
  return out;
}

}  // namespace sandpaper::curation
