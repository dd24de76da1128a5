// library_around (library_here.hpp).
#include "sandpaper/curation/library_here.hpp"

#include <system_error>

namespace sandpaper::curation {

namespace fs = std::filesystem;

std::optional<fs::path> library_around(const fs::path& dir) {
  std::error_code ec;
  fs::path at = fs::absolute(dir, ec).lexically_normal();
  if (ec) return std::nullopt;
  if (at.has_filename() == false && at != at.root_path()) at = at.parent_path();  // "a/b/" -> "a/b"
  for (;;) {
    if (fs::is_regular_file(at / "library.toml", ec)) return at;
    // The top of a work tree: .git is a folder, or a file in a linked worktree or a submodule.
    if (fs::exists(at / ".git", ec)) {
      if (fs::is_regular_file(at / "library" / "library.toml", ec)) return at / "library";
      return std::nullopt;
    }
    if (at == at.root_path() || at.parent_path() == at) return std::nullopt;
    at = at.parent_path();
  }
}

}  // namespace sandpaper::curation
