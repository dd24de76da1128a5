// LayeredIndex::see_through_path and index_of (layers.hpp): the entries of lower roots that the roots
// in front change, compiled over the whole path into an in-memory index, so that show, search and
// near give what explain gives. Each root's own index compiled them over that root and the roots
// below only: a lab's `corduroy` over the world's changes the world's `pinwale-corduroy` (built
// `like corduroy`) on this path, and nowhere else.
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/display_paths.hpp"
#include "sandpaper/curation/layers.hpp"
#include "affected.hpp"
#include "index_write.hpp"
#include "sqlite_util.hpp"

namespace sandpaper::curation {

compiler::Diagnostics LayeredIndex::see_through_path(const std::filesystem::path& calibration_dir, const std::string& device) {
  compiler::Diagnostics failed;
  path_.reset();
  through_.clear();
  path_layer_.clear();
  if (layers_.size() < 2) return failed;
  const auto affected = path_affected(*this, roots_);
  std::vector<std::pair<std::size_t, std::string>> shown;
  std::vector<std::string> qualified;
  for (std::size_t layer = 1; layer < layers_.size(); ++layer)
    for (const auto& name : affected[layer])
      if (!hidden(layer, name)) {
        shown.emplace_back(layer, name);
        qualified.push_back(layers_[layer].id + ":" + name);
      }
  if (shown.empty()) return failed;

  const compiler::CompileOptions options{device, roots_.front(), calibration_dir, roots_};
  const compiler::Compiler c(options, compiler::Library(roots_, layered_files_reached(*this, qualified)));
  const auto& lib = c.library();
  const compiler::DisplayPaths disp(lib);
  sqlite3* db = open_rw(":memory:");
  Closer closer{db};
  sql::exec(db, std::string("BEGIN; ") + kIndexSchemaSql + " COMMIT;");
  EntryWriter writer(db, lib, c.calibration(), disp);
  sql::Stmt version(db, "UPDATE entries SET library_version = ? WHERE name = ?");
  sql::exec(db, "BEGIN");
  for (const auto& [layer, name] : shown) {
    const compiler::LibraryEntry* entry = nullptr;
    for (const auto& e : lib.entries())
      if (e.root == layer && e.name == name) entry = &e;
    if (!entry) continue;  // a second file with a taken name (E0607): its root's rows answer
    auto res = c.compile_file(disp.path_of(*entry));
    if (!res.ok()) {
      for (const auto& d : res.diagnostics.all())
        if (d.severity == compiler::Severity::Error) failed.error(schema::Code::of(d.code), d.location, d.message, d.suggestion).notes = d.notes;
      continue;
    }
    // Its own root's input hash and `depends` rows: what the catalog and near read from any index.
    EntryInputs inputs;
    inputs.hash = layers_[layer].index->input_hash(name).value_or("");
    {
      sql::Stmt dep(layers_[layer].index->handle(), "SELECT kind, target FROM depends WHERE name = ?");
      dep.bind(1, name);
      while (dep.step()) (dep.text(0) == "file" ? inputs.files : inputs.entries).push_back(dep.text(1));
    }
    writer.insert({entry, std::move(*res.material), std::move(*res.program)}, inputs);
    // The version of the library the entry is from, as its root's index says (the path's manifest is the front root's).
    version.bind(1, layers_[layer].index->meta("library_version")).bind(2, name).run();
    through_.emplace(layer, name);
    path_layer_[name] = layer;
  }
  sql::exec(db, "COMMIT");
  // Meta as the front root's index has it (device, maps, Weber fraction), this compiler's own.
  auto meta = index_meta(c, std::filesystem::absolute(roots_.front()).lexically_normal().string(), calibration_dir, device, "", "");
  sql::exec(db, "BEGIN");
  write_families_and_meta(db, lib, meta);
  sql::exec(db, "COMMIT");
  path_ = std::make_unique<Index>(db);
  closer.db = nullptr;
  return failed;
}

const Index& LayeredIndex::index_of(std::size_t layer, const std::string& name) const {
  return path_ && through_path(layer, name) ? *path_ : *layers_.at(layer).index;
}

}  // namespace sandpaper::curation
