// write_catalog_from_layers (catalog.hpp): a layered library's catalog drawn from its roots'
// indexes, so that an edit in one root draws only what it changes over the whole path.
#include <sstream>
#include <stdexcept>

#include "sandpaper/catalog/catalog.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/layers.hpp"

namespace sandpaper::catalog {
namespace {

// Whether `file` lies inside folder `dir` (both as given, made absolute; links not followed).
bool inside(const std::filesystem::path& file, const std::filesystem::path& dir) {
  const auto rel = std::filesystem::absolute(file).lexically_normal().lexically_relative(std::filesystem::absolute(dir).lexically_normal());
  return !rel.empty() && *rel.begin() != "..";
}

// The changed files that are not in a root in front of the bottom one: the bottom root's and the
// calibration's, and any that lie in no root, which the bottom root's update refuses by name.
std::vector<std::filesystem::path> changed_below(const std::vector<std::filesystem::path>& changed,
                                                 const std::vector<std::filesystem::path>& roots) {
  std::vector<std::filesystem::path> out;
  for (const auto& f : changed) {
    bool in_front = false;
    for (std::size_t i = 0; i + 1 < roots.size() && !in_front; ++i) in_front = inside(f, roots[i]);
    if (!in_front) out.push_back(f);
  }
  return out;
}

}  // namespace

std::optional<CatalogReport> write_catalog_from_layers(const std::vector<std::filesystem::path>& roots,
                                                       const std::filesystem::path& calibration_dir, const std::string& device,
                                                       const CatalogOptions& options) {
  if (device != "sim" || roots.size() < 2) return std::nullopt;  // the indexes' inputs are hashed for `sim`
  std::ostringstream sink;
  // Bottom first: a root's index is built over the indexes of the roots below it (docs/LIBRARY.md).
  std::vector<std::filesystem::path> indexes;
  for (const auto& r : roots) indexes.push_back(curation::layer_index_path(r));
  // As the indexes were: every root's fingerprint, and what the roots in front hide by.
  std::vector<std::string> before(roots.size());
  std::vector<std::vector<std::string>> hiding_before(roots.size());
  for (std::size_t i = 0; i < roots.size(); ++i) try {
      const curation::Index idx(indexes[i]);
      before[i] = idx.meta("fingerprint");
      if (i + 1 < roots.size()) hiding_before[i] = idx.names_and_aliases();
    } catch (const curation::IndexError&) {
    }
  std::optional<curation::IndexBuildResult> bottom;
  // Every root's build stats its files, as `library index` does, so an edit in place is seen (the
  // queries' cheaper staleness check is not); the bottom root is updated in place, a root in front
  // reads only what its entries reach below.
  for (std::size_t i = roots.size(); i-- > 0;) {
    const std::vector<std::filesystem::path> below(roots.begin() + static_cast<std::ptrdiff_t>(i) + 1, roots.end());
    curation::Progress quiet("indexing", 0, true, sink, false);
    curation::IndexOptions io{roots[i], calibration_dir, indexes[i], device};
    io.below = below;
    // Told what changed, the bottom root (the world, updated in place) stats only those of its files
    // and the calibration's; a root in front is small and walks itself.
    if (options.changed && below.empty()) io.changed = changed_below(*options.changed, roots);
    const auto built = curation::build_index(io, quiet);
    if (io.changed && !built.ok && built.error.find("the changed file") == 0) throw std::invalid_argument(built.error);
    if (!built.ok) return std::nullopt;
    if (below.empty()) bottom = built;
  }
  const curation::LayeredIndex idx(roots, indexes);
  CatalogSource source;
  source.manifest = compiler::Library(roots, std::vector<std::vector<std::string>>(roots.size())).manifest();
  // The bottom root updated in place, and the roots in front hiding by the same names: only the
  // bottom rows it rewrote can have changed there, so those, every entry of the roots in front and
  // what reaches them are compared, if the record was compared with the path as it was.
  bool few = bottom && bottom->rewritten && bottom->rewritten->size() <= 256;
  for (std::size_t i = 0; few && i + 1 < roots.size(); ++i) few = !before[i].empty() && idx.index(i).names_and_aliases() == hiding_before[i];
  auto inputs = curation::layered_inputs(idx, roots, few ? &*bottom->rewritten : nullptr);
  source.index_fingerprint = inputs.fingerprint;
  if (few && !inputs.gone) {
    before.back() = bottom->previous_fingerprint;
    source.since = curation::layered_fingerprint(inputs.global, idx, before);
    source.entry_count = inputs.shown;
    source.every_entry = [&] { return curation::layered_inputs(idx, roots).entries; };
  } else if (few) {
    inputs = curation::layered_inputs(idx, roots);
  }
  source.entries = std::move(inputs.entries);
  source.hides = [&](const std::string& name) {
    const auto at = idx.resolve(name);
    return at ? idx.hides(at->first, at->second) : std::string();
  };
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
