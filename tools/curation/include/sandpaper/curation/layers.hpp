#pragma once
// Queries over a layered library path (docs/LIBRARY.md, "Layered libraries"): a lab's library on
// top of the world's. Every root has its own index (layer_index_path, built with the roots below
// it: IndexOptions::below); an entry of a root in front hides an entry of the same name below, as
// it does for the compiler. Entries come back with IndexedEntry::root set to their root's id.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

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

  // search() over every root: exact names first, then aliases, then word matches by bm25 (without
  // words: by roughness); ties front root first; hidden entries left out. Throws
  // std::invalid_argument for a family no root has.
  std::vector<SearchHit> search(const SearchQuery& q) const;
  // The `limit` perceptually nearest entries, of any root, to `name` of root `layer`.
  std::vector<Neighbour> nearest(std::size_t layer, const std::string& name, std::size_t limit) const;
  // Every name and alias, for "did you mean" (qualified ID:NAME too).
  std::vector<std::string> names_and_aliases() const;

 private:
  struct Layer {
    std::string id;
    std::unique_ptr<Index> index;
  };
  std::vector<Layer> layers_;
};

}  // namespace sandpaper::curation
