#pragma once
// Where library files are shown in diagnostics. The compiler names library files "library/<rel>";
// curation tools show them as the curator would open them: relative to the working directory when
// the library lies below it, else by absolute path.
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include <utility>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/library.hpp"

namespace sandpaper::curation {

class DisplayPaths {
 public:
  explicit DisplayPaths(const std::filesystem::path& library_dir);
  // Every root of a layered library ("library/<id>/<rel>" as the compiler names their files).
  explicit DisplayPaths(const compiler::Library& library);
  // "library/textiles/corduroy.hmat" (relative to cwd) or "/tmp/x/textiles/corduroy.hmat", in the front root.
  std::string path_of(const std::string& relative_path) const;
  // An entry's file as shown, in whichever root it is.
  std::string path_of(const compiler::LibraryEntry& e) const;
  // The location moved into a SourceFile of the same text with the display name, if it points into
  // a file the compiler calls "library/<rel>"; other locations are returned unchanged.
  compiler::SourceLocation relocate(const compiler::SourceLocation& loc) const;
  compiler::Diagnostic relocate(const compiler::Diagnostic& d) const;
  void append_relocated(compiler::Diagnostics& to, const compiler::Diagnostics& from) const;

 private:
  std::string prefix_;  // the front root's; ends with '/'
  std::vector<std::pair<std::string, std::string>> roots_;  // (compiler's prefix, shown prefix), by root
  mutable std::map<std::string, std::shared_ptr<const compiler::SourceFile>> cache_;  // by the compiler's name
};

}  // namespace sandpaper::curation
