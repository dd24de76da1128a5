// write_catalog_from_index (catalog.hpp): the catalog's inputs read off the library's index, so
// that a catalog run reads only the entries it draws (at 100,000 entries, reading and hashing
// every entry file was most of a one-entry update).
#include <sstream>
#include <stdexcept>

#include "sandpaper/catalog/catalog.hpp"
#include "sandpaper/curation/index.hpp"

namespace sandpaper::catalog {

std::optional<CatalogReport> write_catalog_from_index(const std::filesystem::path& library_dir,
                                                      const std::filesystem::path& calibration_dir, const std::string& device,
                                                      const CatalogOptions& options) {
  if (device != "sim") return std::nullopt;  // the index's inputs are hashed for its device
  const auto index_path = curation::default_index_path(library_dir);
  std::ostringstream sink;
  curation::Progress quiet("indexing", 0, true, sink, false);
  curation::IndexOptions io{library_dir, calibration_dir, index_path, device};
  io.changed = options.changed;
  const auto indexed = curation::build_index(io, quiet);
  // A list naming files of another folder is the caller's mistake, not a reason to draw without the index.
  if (options.changed && !indexed.ok && indexed.error.find("the changed file") == 0) throw std::invalid_argument(indexed.error);
  if (!indexed.ok) return std::nullopt;
  const curation::Index idx(index_path);
  CatalogSource source;
  source.manifest = compiler::Library(library_dir, std::vector<std::string>{}).manifest();
  source.index_fingerprint = idx.meta("fingerprint");
  if (indexed.rewritten) {
    // Updated in place: if the record was compared with the index as it was, only these can differ.
    // A name with no row now is gone: then the whole list (write_catalog removes its files).
    bool gone = false;
    for (const auto& name : *indexed.rewritten) {
      const auto hash = idx.input_hash(name);
      gone = gone || !hash;
      if (hash) source.entries.emplace_back(name, *hash);
    }
    source.since = gone ? std::string() : indexed.previous_fingerprint;
    source.entry_count = indexed.entries;
    source.every_entry = [&idx] { return idx.input_hashes(); };
  } else {
    source.entries = idx.input_hashes();
  }
  std::optional<compiler::Compiler> drawing;
  source.compiler_for = [&](const std::vector<std::string>& names) -> const compiler::Compiler& {
    compiler::CompileOptions o;
    o.device = device;
    o.library_dir = library_dir;
    o.calibration_dir = calibration_dir;
    drawing.emplace(o, compiler::Library(library_dir, idx.files_reached(names)));
    return *drawing;
  };
  return write_catalog(source, options);
}

}  // namespace sandpaper::catalog
