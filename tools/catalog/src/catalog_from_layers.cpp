// write_catalog_from_layers (catalog.hpp): a layered library's catalog drawn from its roots'
// indexes, so that an edit in one root draws only what it changes over the whole path.
#include <sstream>

#include "sandpaper/catalog/catalog.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/layers.hpp"

namespace sandpaper::catalog {

std::optional<CatalogReport> write_catalog_from_layers(const std::vector<std::filesystem::path>& roots,
                                                       const std::filesystem::path& calibration_dir, const std::string& device,
                                                       const CatalogOptions& options) {
  if (device != "sim" || roots.size() < 2) return std::nullopt;  // the indexes' inputs are hashed for `sim`
  std::ostringstream sink;
  // Bottom first: a root's index is built over the indexes of the roots below it (docs/LIBRARY.md).
  std::vector<std::filesystem::path> indexes;
  for (const auto& r : roots) indexes.push_back(curation::layer_index_path(r));
  // Every root's build stats its files, as `library index` does, so an edit in place is seen (the
  // queries' cheaper staleness check is not); the bottom root is updated in place, a root in front
  // reads only what its entries reach below.
  for (std::size_t i = roots.size(); i-- > 0;) {
    const std::vector<std::filesystem::path> below(roots.begin() + static_cast<std::ptrdiff_t>(i) + 1, roots.end());
    curation::Progress quiet("indexing", 0, true, sink, false);
    curation::IndexOptions io{roots[i], calibration_dir, indexes[i], device};
    io.below = below;
    if (!curation::build_index(io, quiet).ok) return std::nullopt;
  }
  const curation::LayeredIndex idx(roots, indexes);
  auto inputs = curation::layered_inputs(idx, roots);
  CatalogSource source;
  source.manifest = compiler::Library(roots, std::vector<std::vector<std::string>>(roots.size())).manifest();
  source.index_fingerprint = inputs.fingerprint;
  source.entries = std::move(inputs.entries);
  std::optional<compiler::Compiler> drawing;
  source.compiler_for = [&](const std::vector<std::string>& names) -> const compiler::Compiler& {
    compiler::CompileOptions o;
    o.device = device;
    o.library_dir = roots.front();
    o.library_path = roots;
    o.calibration_dir = calibration_dir;
    drawing.emplace(o, compiler::Library(roots, curation::layered_files_reached(idx, names)));
    return *drawing;
  };
  return write_catalog(source, options);
}

}  // namespace sandpaper::catalog
