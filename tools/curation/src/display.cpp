#include "sandpaper/curation/display.hpp"

#include <algorithm>

namespace sandpaper::curation {

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
  for (const auto& r : library.roots())
    roots_.emplace_back(library.layered() ? std::string(kCompilerPrefix) + r.id + "/" : std::string(kCompilerPrefix),
                        shown_prefix(r.dir));
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
    auto& added = r.severity == compiler::Severity::Error ? moved.error(r.code, r.location, r.message, r.suggestion)
                                                          : moved.warning(r.code, r.location, r.message, r.suggestion);
    added.notes = r.notes;
    added.severity = r.severity;
  }
  to.append(moved);
}

}  // namespace sandpaper::curation
