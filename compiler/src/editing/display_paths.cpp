#include "sandpaper/compiler/display_paths.hpp"

#include <algorithm>

namespace sandpaper::compiler {

namespace {
constexpr std::string_view kCompilerPrefix = "library/";  // how Library names its entries' files
}

namespace {
std::string shown_prefix(const std::filesystem::path& library_dir) {
  std::error_code ec;
  auto abs = std::filesystem::weakly_canonical(std::filesystem::absolute(library_dir, ec), ec);
  auto cwd = std::filesystem::current_path(ec);
  auto rel = abs.lexically_relative(cwd);
  std::string r = rel.generic_string();
  if (!rel.empty() && r.rfind("..", 0) != 0) return r == "." ? std::string() : r + "/";
  return abs.generic_string() + "/";
}
}  // namespace

DisplayPaths::DisplayPaths(const std::filesystem::path& library_dir) : prefix_(shown_prefix(library_dir)) {
  roots_.emplace_back(std::string(kCompilerPrefix), prefix_);
}

DisplayPaths::DisplayPaths(const compiler::Library& library) : prefix_(shown_prefix(library.directory())) {
  for (const auto& r : library.roots()) {
    roots_.emplace_back(library.layered() ? std::string(kCompilerPrefix) + r.id + "/" : std::string(kCompilerPrefix),
                        shown_prefix(r.dir));
    std::error_code ec;
    absolute_.emplace_back(std::filesystem::absolute(r.dir, ec).lexically_normal().generic_string() + "/", roots_.back().second);
  }
}

DisplayPaths::DisplayPaths(const std::vector<std::pair<std::string, std::filesystem::path>>& roots)
    : prefix_(roots.empty() ? std::string() : shown_prefix(roots.front().second)) {
  for (const auto& [id, dir] : roots) {
    roots_.emplace_back(roots.size() > 1 ? std::string(kCompilerPrefix) + id + "/" : std::string(kCompilerPrefix), shown_prefix(dir));
    std::error_code ec;
    absolute_.emplace_back(std::filesystem::absolute(dir, ec).lexically_normal().generic_string() + "/", roots_.back().second);
  }
}

DisplayPaths::DisplayPaths(const compiler::Library& library, FromRootsParent) {
  for (const auto& r : library.roots()) {
    std::error_code ec;
    const auto dir = std::filesystem::absolute(r.dir, ec).lexically_normal();
    const auto name = (dir.has_filename() ? dir.filename() : dir.parent_path().filename()).generic_string() + "/";
    roots_.emplace_back(library.layered() ? std::string(kCompilerPrefix) + r.id + "/" : std::string(kCompilerPrefix), name);
    absolute_.emplace_back(dir.generic_string() + (dir.has_filename() ? "/" : ""), name);
  }
  prefix_ = roots_.empty() ? std::string() : roots_.front().second;
}

std::string DisplayPaths::in_text(const std::string& text) const {
  // Longest prefix first: "library/world/" before "library/".
  std::vector<std::pair<std::string, std::string>> all = absolute_;
  all.insert(all.end(), roots_.begin(), roots_.end());
  std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first.size() > b.first.size(); });
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const bool starts = i == 0 || text[i - 1] == ' ' || text[i - 1] == '(' || text[i - 1] == '[' || text[i - 1] == '\n';
    const auto hit = !starts ? all.end() : std::find_if(all.begin(), all.end(), [&](const auto& p) {
      return text.compare(i, p.first.size(), p.first) == 0;
    });
    if (hit != all.end()) {
      out += hit->second;
      i += hit->first.size();
    } else {
      out += text[i++];
    }
  }
  return out;
}

std::string DisplayPaths::path_of(const std::string& relative_path) const { return prefix_ + relative_path; }

std::string DisplayPaths::path_of(const compiler::LibraryEntry& e) const {
  return (e.root < roots_.size() ? roots_[e.root].second : prefix_) + e.relative_path;
}

compiler::SourceLocation DisplayPaths::relocate(const compiler::SourceLocation& loc) const {
  if (!loc.file) return loc;
  const auto root = std::find_if(roots_.begin(), roots_.end(), [&](const auto& r) { return loc.file->name.rfind(r.first, 0) == 0; });
  if (root == roots_.end()) return loc;
  auto& shown = cache_[loc.file->name];
  if (!shown)
    shown = std::make_shared<const compiler::SourceFile>(root->second + loc.file->name.substr(root->first.size()), loc.file->text);
  auto out = loc;
  out.file = shown;
  return out;
}

compiler::Diagnostic DisplayPaths::relocate(const compiler::Diagnostic& d) const {
  auto out = d;
  out.location = relocate(d.location);
  for (auto& n : out.notes) n.location = relocate(n.location);
  return out;
}

void DisplayPaths::append_relocated(compiler::Diagnostics& to, const compiler::Diagnostics& from) const {
  compiler::Diagnostics moved;
  for (const auto& d : from.all()) {
    auto r = relocate(d);
    auto& added = r.severity == compiler::Severity::Error ? moved.error(schema::Code::of(r.code), r.location, r.message, r.suggestion)
                                                          : moved.warning(schema::Code::of(r.code), r.location, r.message, r.suggestion);
    added.notes = r.notes;
    added.severity = r.severity;
  }
  to.append(moved);
}

}  // namespace sandpaper::compiler
