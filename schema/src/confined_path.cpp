#include "sandpaper/schema/confined_path.hpp"

#include <system_error>

namespace sandpaper::schema {

std::filesystem::path confined_path(const std::filesystem::path& root, const std::string& relative,
                                    const std::string& folder, const std::string& rule) {
  namespace fs = std::filesystem;
  if (relative.empty()) throw OutsideFolder("an empty path names no file in " + folder);
  if (relative.find('\0') != std::string::npos) throw OutsideFolder("a path may not contain NUL");
  const fs::path rel(relative);
  if (rel.is_absolute() || rel.has_root_name() || rel.has_root_directory())
    throw OutsideFolder("'" + relative + "' is an absolute path; give a path relative to " + folder);
  std::error_code ec;
  const fs::path base = fs::canonical(root, ec);
  if (ec) throw OutsideFolder(folder + " cannot be resolved: " + ec.message());
  // `..` is applied before symlinks are resolved: weakly_canonical keeps "missing/../link" lexical
  // past a component that does not exist, so a link there would lead out unseen. Errors (a name too
  // long, a link loop) are refusals, not exceptions.
  const fs::path full = fs::weakly_canonical(base / rel.lexically_normal(), ec);
  if (ec) throw OutsideFolder("'" + relative + "' cannot be resolved in " + folder + ": " + ec.message());
  // Lexically inside: every component of base is a prefix of full's.
  auto b = base.begin();
  auto f = full.begin();
  for (; b != base.end(); ++b, ++f)
    if (f == full.end() || *b != *f)
      throw OutsideFolder("'" + relative + "' is outside " + folder + " " + base.string() + (rule.empty() ? "" : "; " + rule));
  return full;
}

}  // namespace sandpaper::schema
