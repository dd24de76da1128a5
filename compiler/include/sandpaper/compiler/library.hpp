#pragma once
// The world haptics library (thesis 1.6): representative descriptions (`like corduroy`) are material
// files under library/, one entry a file, `<family>/<name>.hmat`, named by their file stem or by any
// of their aliases; library/library.toml gives the library's name, version and families.
// A library path is several such folders, searched front to back (a lab's own library on top of
// the world library): a name is the first root's that has it; `like world:corduroy` names the
// root by its `id` (docs/LIBRARY.md, "Layered libraries").
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/syntax.hpp"

namespace sandpaper::compiler {

struct LibraryFamily {
  std::string id;         // "textiles", as entries write `family textiles`
  std::string title;      // "Textiles"
  std::string describes;  // one line for catalogues
  // A published stimulus set (the thesis' Table 8, ...): its entries share force levels by design,
  // so `library check` does not warn that they are less than one force JND apart.
  bool stimulus_set = false;
};

// library/library.toml. Missing file: everything empty (a bare folder of .hmat files still works).
struct LibraryManifest {
  std::string id;         // the root's short name, for `like ID:NAME` ("world"); empty: the folder's name
  std::string name;
  std::string version;    // semantic version of the library's content ("1.0.0")
  std::string reference;  // the entry a bare perceptual description starts from ("reference-grating")
  std::vector<LibraryFamily> families;  // in display order
  std::filesystem::path file;           // the manifest's path; empty if there is none
  const LibraryFamily* family(const std::string& family_id) const;
};

// One entry as written: its metadata read off the syntax (nothing resolved or compiled).
struct LibraryEntry {
  std::string name;                  // the file stem; the `material "name"` must agree (library check)
  std::filesystem::path file;        // full path
  std::string relative_path;         // "textiles/corduroy.hmat", relative to the library folder
  std::string family, describes, licence, deprecated_by;  // empty when the entry does not say
  std::vector<std::string> aliases;
  std::vector<std::string> likes;    // names given to `like`, in order
  MaterialSyntax syntax;             // parsed; statements carry their `source` notes
  bool parsed_ok = false;            // no lexer or parser errors
  bool overrides = false;            // says `overrides`: it means to hide an entry of a root below
  std::size_t root = 0;              // index into Library::roots(), 0 = the front
};

// One folder of a library path.
struct LibraryRoot {
  std::filesystem::path dir;
  LibraryManifest manifest;
  std::string id;  // manifest.id, else the folder's name
};

class Library {
 public:
  // Scans `dir` recursively for *.hmat files and reads library.toml. Problems (unreadable manifest,
  // syntax errors in an entry) do not throw: they are kept in scan_diagnostics().
  explicit Library(std::filesystem::path dir);
  // Several roots, front first. An empty list is one root, default_library_dir().
  explicit Library(std::vector<std::filesystem::path> roots);
  // Part of one folder: only these entry files ("textiles/corduroy.hmat", relative to `dir`; absent
  // ones are left out), with its library.toml. Enough to compile entries whose `like` chains and
  // reference lie within it; what an incremental index build uses instead of reading every file.
  Library(std::filesystem::path dir, const std::vector<std::string>& only_files);
  // Part of several roots, front first: only `only_files[i]` of root i (relative to it), with every
  // root's library.toml. Names resolve as over the whole path as long as each root holds the file
  // of every name its `like` chains reach there (a layered catalog draws a few entries this way).
  Library(std::vector<std::filesystem::path> roots, const std::vector<std::vector<std::string>>& only_files);

  // Entry names (file stems), sorted.
  std::vector<std::string> names() const;
  // The entry's file for a name or an alias, or nullopt if there is no such entry. Every lookup
  // takes NAME (the first root that has it as a name or alias) or ID:NAME (that root only).
  std::optional<std::filesystem::path> find(const std::string& name_or_alias) const;
  // The entry's name for a name or an alias.
  std::optional<std::string> canonical_name(const std::string& name_or_alias) const;
  const LibraryEntry* entry(const std::string& name_or_alias) const;
  const std::vector<LibraryEntry>& entries() const { return entries_; }  // sorted by name, then root
  // The front root's name and version; the first reference any root declares; every root's families.
  const LibraryManifest& manifest() const { return manifest_; }
  const Diagnostics& scan_diagnostics() const { return scan_diags_; }
  const std::filesystem::path& directory() const { return roots_.front().dir; }  // the front root
  const std::vector<LibraryRoot>& roots() const { return roots_; }
  bool layered() const { return roots_.size() > 1; }

  // "corduroy", or "world:corduroy" when there are several roots.
  std::string qualified_name(const LibraryEntry& e) const;
  // The name the compiler gives an entry's file in diagnostics and provenance:
  // "library/textiles/corduroy.hmat", or "library/world/textiles/corduroy.hmat" when layered.
  std::string source_name(const LibraryEntry& e) const;
  // The root folder and the path inside it of a source_name(); nullopt for any other name.
  std::optional<std::pair<std::filesystem::path, std::string>> source_file(const std::string& source_name) const;
  // Where the thesis' version-1 readings are (thesis/version1.toml): the first root that has them.
  std::filesystem::path thesis_directory() const;
  // An entry of a root below that `e` hides (same name or alias), or nullptr.
  const LibraryEntry* shadowed_by(const LibraryEntry& e) const;

 private:
  void read_roots(std::vector<std::filesystem::path> roots);
  void scan(std::size_t root, const std::vector<std::string>* only_files = nullptr);
  void index_names();
  // The entry name root `root` gives `name_or_alias` (library_layers.hpp's question), or nullopt.
  std::optional<std::string> knows(std::size_t root, const std::string& name_or_alias) const;
  std::vector<LibraryRoot> roots_;
  LibraryManifest manifest_;
  std::vector<LibraryEntry> entries_;
  // name -> index, then alias -> index for aliases that are not also a name (names win), root by
  // root from the front; and the same for each root alone.
  std::map<std::string, std::size_t> by_name_;
  std::vector<std::map<std::string, std::size_t>> by_root_;
  Diagnostics scan_diags_;
};

// Reads the material file's metadata statements into `e` (family, aliases, licence, ...).
void read_entry_metadata(LibraryEntry& e);

// find_library_dir().dir: $SANDPAPER_LIBRARY, $SANDPAPER_DATA_DIR/library, else the shipped library
// (the source tree's in a build tree, the installed package's when installed; data_dirs.hpp).
std::filesystem::path default_library_dir();
// $SANDPAPER_LIBRARY_PATH split at ':' (front first), else { default_library_dir() }.
std::vector<std::filesystem::path> default_library_path();
// "lab:/srv/world" -> {"lab", "/srv/world"}; empty parts are left out.
std::vector<std::filesystem::path> split_library_path(const std::string& text);

}  // namespace sandpaper::compiler
