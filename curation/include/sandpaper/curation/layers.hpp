#pragma once
// Queries over a layered library path (docs/LIBRARY.md, "Layered libraries"): a lab's library on
// top of the world's. Every root has its own index (layer_index_path, built with the roots below
// it: IndexOptions::below); an entry of a root in front hides an entry of the same name below, as
// it does for the compiler. Entries come back with IndexedEntry::root set to their root's id.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/near.hpp"
#include "sandpaper/curation/search.hpp"

namespace sandpaper::curation {

// A root's id as its index records it (library.toml `id`, else the folder's name), as the
// compiler names the root in `like ID:NAME`.
std::string root_id(const Index& index, const std::filesystem::path& root_dir);

class LayeredIndex {
 public:
  // `roots` front first. Opens each root's index (`index_paths`, parallel to `roots`; empty: each
  // root's layer_index_path()); throws IndexError naming the root whose index cannot be read
  // (build it: `sandpaper library index --library A:B`).
  explicit LayeredIndex(const std::vector<std::filesystem::path>& roots, const std::vector<std::filesystem::path>& index_paths = {});

  std::size_t size() const { return layers_.size(); }
  const Index& index(std::size_t layer) const { return *layers_[layer].index; }
  const std::string& id(std::size_t layer) const { return layers_[layer].id; }

  // NAME (the first root that has it as a name or alias) or ID:NAME (that root only): the root and
  // the entry's name there; nullopt if none has it.
  std::optional<std::pair<std::size_t, std::string>> resolve(const std::string& name_or_alias) const;
  // Whether a root in front of `layer` has an entry named `name` (which then hides this one).
  bool hidden(std::size_t layer, const std::string& name) const;
  std::optional<IndexedEntry> entry(std::size_t layer, const std::string& name) const;
  // The entry of a root below `layer` that entry `name` of `layer` hides by its name or an alias,
  // as "ID:NAME" (compiler::Library::shadowed_by's, by the indexes); "" if none.
  std::string hides(std::size_t layer, const std::string& name) const;

  // Compiles on `device`, over the whole path, every entry of a root below the front one that the
  // roots in front may change (its `like` chain, reference or replacement reaches a name a root in
  // front defines, or the thesis' readings there), as explain compiles it; entry(), index_of(),
  // search() and nearest() then answer for those entries with what the compiler gives over the
  // path, not with their root's own rows (docs/LIBRARY.md, "Queries see what the compiler sees").
  // Returns the errors of entries that do not compile over the path (their root's rows answer for
  // them). Throws calibration::CalibrationError for unreadable calibration.
  compiler::Diagnostics see_through_path(const std::filesystem::path& calibration_dir, const std::string& device = "sim");
  // The index whose rows (statements, provenance, meta) answer for entry `name` of root `layer`.
  const Index& index_of(std::size_t layer, const std::string& name) const;
  // Whether entry `name` of root `layer` was compiled over the path by see_through_path().
  bool through_path(std::size_t layer, const std::string& name) const { return through_.count({layer, name}) > 0; }

  // search() over every root: exact names first, then aliases, then word matches by word_score
  // (without words: by roughness); ties by name, then front root first; hidden entries left out.
  // Throws std::invalid_argument for a family no root has.
  std::vector<SearchHit> search(const SearchQuery& q) const;
  // The `limit` perceptually nearest entries, of any root, to `name` of root `layer`.
  // Of family `family` only, unless it is empty.
  std::vector<Neighbour> nearest(std::size_t layer, const std::string& name, std::size_t limit,
                                 const std::string& family = "") const;
  // Every name and alias, for "did you mean" (qualified ID:NAME too).
  std::vector<std::string> names_and_aliases() const;

 private:
  struct Layer {
    std::string id;
    std::unique_ptr<Index> index;
  };
  std::vector<Layer> layers_;
  std::vector<std::filesystem::path> roots_;
  // see_through_path(): the affected entries' rows compiled over the path (in memory), and which
  // root each is of.
  std::unique_ptr<Index> path_;
  std::set<std::pair<std::size_t, std::string>> through_;
  std::map<std::string, std::size_t> path_layer_;
};

// What a layered library's catalog compares (docs/CATALOG.md, "A layered library"): every entry
// the path shows (an entry hidden by a name or alias of a root in front is left out), sorted by
// name, with a hash of what its compiled form and page depend on over the whole path: its own
// root's input hash (its file, images, chain in that root, calibration, compiler, device, the roots
// below), the roots' ids, folders and library.toml files and where the thesis' readings come
// from; and, for an entry whose `like` chain, reference or replacement reaches a name that a root
// in front of its own defines (so that the path resolves it otherwise than its root's index did),
// the hashes over the path of what those names resolve to there, recursively. Reads each root's
// `inputs`, names and a few `depends` rows: no entry file.
struct LayeredInputs {
  std::vector<std::pair<std::string, std::string>> entries;  // (name, hex hash), sorted by name
  std::string global;        // hex hash of what every entry shares (roots, their library.toml, the thesis' root)
  std::string fingerprint;   // layered_fingerprint(global, every root's index fingerprint): changes with any file of the path
  std::size_t affected = 0;  // listed entries that reach a root in front of their own
  std::size_t shown = 0;     // entries the path shows in all
  bool gone = false;         // one of `bottom_names` has no row in the bottom root's index
};
// `roots` as the LayeredIndex was opened with, front first; their indexes must be fresh. With
// `bottom_names`, lists of the bottom root only those entries and the ones that reach a root in
// front (every entry of the other roots still): what a catalog compares after an in-place update
// of the bottom root that rewrote those rows (docs/CATALOG.md, "A layered library").
LayeredInputs layered_inputs(const LayeredIndex& idx, const std::vector<std::filesystem::path>& roots,
                             const std::vector<std::string>* bottom_names = nullptr);
// "global GLOBAL\nID FINGERPRINT\n..." over the roots front first: a layered catalog's record keeps
// it, as a single root's keeps its index's fingerprint.
std::string layered_fingerprint(const std::string& global, const LayeredIndex& idx, const std::vector<std::string>& fingerprints);

// For each root (front first), the entry files (relative to it) that compiling `names` over the
// path reads: theirs, those of every entry they are built on through `like` (each name resolved
// front first, as the compiler does), the reference entry's, and those of the entries they name
// as replacements. compiler::Library(roots, these) compiles and links them as the whole path does.
std::vector<std::vector<std::string>> layered_files_reached(const LayeredIndex& idx, const std::vector<std::string>& names);

}  // namespace sandpaper::curation
