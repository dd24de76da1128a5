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

namespace sandpaper::compiler {

class DisplayPaths {
 public:
  explicit DisplayPaths(const std::filesystem::path& library_dir);
  // Every root of a layered library ("library/<id>/<rel>" as the compiler names their files).
  explicit DisplayPaths(const Library& library);
  // Relative to the folder that holds each root ("world/textiles/corduroy.hmat"), whatever the
  // working directory: what a page published apart from this machine shows (the catalog). The same
  // text the CLI prints when run from that folder.
  // The roots of a library path as (id, folder), front first, without reading the library.
  explicit DisplayPaths(const std::vector<std::pair<std::string, std::filesystem::path>>& roots);
  struct FromRootsParent {};
  DisplayPaths(const Library& library, FromRootsParent);
  // `text` with every library file the compiler names ("library/<rel>", "library/<id>/<rel>") or
  // gives by its absolute path (a root's folder), where a path starts (at the start, after a
  // space, '(' or '['), shown as above: explain's provenance, a catalog page's sources.
  std::string in_text(const std::string& text) const;
  // "library/textiles/corduroy.hmat" (relative to cwd) or "/tmp/x/textiles/corduroy.hmat", in the front root.
  std::string path_of(const std::string& relative_path) const;
  // An entry's file as shown, in whichever root it is.
  std::string path_of(const LibraryEntry& e) const;
  // The location moved into a SourceFile of the same text with the display name, if it points into
  // a file the compiler calls "library/<rel>"; other locations are returned unchanged.
  SourceLocation relocate(const SourceLocation& loc) const;
  Diagnostic relocate(const Diagnostic& d) const;
  void append_relocated(Diagnostics& to, const Diagnostics& from) const;

 private:
  std::string prefix_;  // the front root's; ends with '/'
  std::vector<std::pair<std::string, std::string>> roots_;  // (compiler's prefix, shown prefix), by root
  std::vector<std::pair<std::string, std::string>> absolute_;  // (a root's absolute folder + '/', shown prefix)
  mutable std::map<std::string, std::shared_ptr<const SourceFile>> cache_;  // by the compiler's name
};

}  // namespace sandpaper::compiler
