#pragma once
// The world haptics library (thesis 1.6): representative descriptions (`like corduroy`) are material
// files under library/, one entry a file, `<family>/<name>.hmat`, named by their file stem or by any
// of their aliases; library/library.toml gives the library's name, version and families.
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
  std::string name;
  std::string version;    // semantic version of the library's content ("1.0.0")
  std::string reference;  // the entry a bare perceptual description starts from ("reference-grating")
  std::vector<LibraryFamily> families;  // in display order
  std::filesystem::path file;           // the manifest's path; empty if there is none
  const LibraryFamily* family(const std::string& id) const;
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
};

class Library {
 public:
  // Scans `dir` recursively for *.hmat files and reads library.toml. Problems (unreadable manifest,
  // syntax errors in an entry) do not throw: they are kept in scan_diagnostics().
  explicit Library(std::filesystem::path dir);

  // Entry names (file stems), sorted.
  std::vector<std::string> names() const;
  // The entry's file for a name or an alias, or nullopt if there is no such entry.
  std::optional<std::filesystem::path> find(const std::string& name_or_alias) const;
  // The entry's name for a name or an alias.
  std::optional<std::string> canonical_name(const std::string& name_or_alias) const;
  const LibraryEntry* entry(const std::string& name_or_alias) const;
  const std::vector<LibraryEntry>& entries() const { return entries_; }  // sorted by name
  const LibraryManifest& manifest() const { return manifest_; }
  const Diagnostics& scan_diagnostics() const { return scan_diags_; }
  const std::filesystem::path& directory() const { return dir_; }

 private:
  std::filesystem::path dir_;
  LibraryManifest manifest_;
  std::vector<LibraryEntry> entries_;
  // name -> index, then alias -> index for aliases that are not also a name (names win).
  std::map<std::string, std::size_t> by_name_;
  Diagnostics scan_diags_;
};

// Reads the material file's metadata statements into `e` (family, aliases, licence, ...).
void read_entry_metadata(LibraryEntry& e);

// find_library_dir().dir: $SANDPAPER_LIBRARY, $SANDPAPER_DATA_DIR/library, else the shipped library
// (the source tree's in a build tree, the installed package's when installed; data_dirs.hpp).
std::filesystem::path default_library_dir();

}  // namespace sandpaper::compiler
