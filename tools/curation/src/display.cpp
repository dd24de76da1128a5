#include "sandpaper/curation/display.hpp"

namespace sandpaper::curation {

namespace {
constexpr std::string_view kCompilerPrefix = "library/";  // how Library names its entries' files
}

DisplayPaths::DisplayPaths(const std::filesystem::path& library_dir) {
  std::error_code ec;
  auto abs = std::filesystem::weakly_canonical(std::filesystem::absolute(library_dir, ec), ec);
  auto cwd = std::filesystem::current_path(ec);
  auto rel = abs.lexically_relative(cwd);
  std::string r = rel.generic_string();
  if (!rel.empty() && r.rfind("..", 0) != 0) prefix_ = (r == "." ? std::string() : r + "/");
  else prefix_ = abs.generic_string() + "/";
}

std::string DisplayPaths::path_of(const std::string& relative_path) const { return prefix_ + relative_path; }

compiler::SourceLocation DisplayPaths::relocate(const compiler::SourceLocation& loc) const {
  if (!loc.file || loc.file->name.rfind(kCompilerPrefix, 0) != 0) return loc;
  auto& shown = cache_[loc.file->name];
  if (!shown)
    shown = std::make_shared<const compiler::SourceFile>(path_of(loc.file->name.substr(kCompilerPrefix.size())), loc.file->text);
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
