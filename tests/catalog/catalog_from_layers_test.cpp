// write_catalog_from_layers: a layered library's catalog drawn from its roots' indexes, drawing
// only what an edit changes over the whole path, must be the catalog of the whole path, byte for
// byte (issue 18; docs/CATALOG.md, "A layered library").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "sandpaper/catalog/catalog.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/layers.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {
namespace fs = std::filesystem;
using test::replace_in;

// Every file but the record, whose rows a catalog drawn without indexes has no hashes for.
std::map<std::string, std::string> pages_under(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) {
      const auto rel = fs::relative(e.path(), dir).generic_string();
      if (rel == "inputs.sqlite") continue;
      std::ifstream in(e.path(), std::ios::binary);
      out[rel] = std::string(std::istreambuf_iterator<char>(in), {});
    }
  return out;
}

// The files that differ, or are in one folder only: a short message where a diff of the texts would be pages.
std::vector<std::string> differing(const std::map<std::string, std::string>& a, const std::map<std::string, std::string>& b) {
  std::vector<std::string> out;
  for (const auto& [name, text] : a)
    if (const auto it = b.find(name); it == b.end() || it->second != text) out.push_back(name);
  for (const auto& [name, text] : b)
    if (!a.count(name)) out.push_back(name + " (only in the second)");
  return out;
}

// world: corduroy (alias wide-wale), the reference grating, canvas, sturdy (like canvas), pinwale
// (like corduroy: over the path, the lab's), a bare roughness (on the reference); lab: its own
// corduroy on the world's, hiding it, and felt on wide-wale (the world's corduroy by its alias).
struct Path {
  fs::path root, lab, world;
  explicit Path(const std::string& tag) : root(test::temp_dir(tag)), lab(root / "lab"), world(root / "world") {
    test::write_text(world / "library.toml",
                     "id = \"world\"\nname = \"world\"\nversion = \"1.0.0\"\nreference = \"reference-grating\"\n"
                     "[families.cloth]\ntitle = \"Cloth\"\n");
    test::write_text(world / "cloth/corduroy.hmat",
                     "material \"corduroy\" {\n  family cloth\n  alias wide-wale\n  describes \"wide-wale corduroy\"\n"
                     "  grating period 3 mm hill 60%\n  roughness 0.4\n}\n");
    test::write_text(world / "cloth/reference-grating.hmat",
                     "material \"reference-grating\" {\n  grating period 2.5 mm\n  roughness 0.5\n}\n");
    test::write_text(world / "cloth/canvas.hmat",
                     "material \"canvas\" {\n  family cloth\n  describes \"canvas\"\n  grating period 1.5 mm\n  roughness 0.3\n}\n");
    test::write_text(world / "cloth/sturdy.hmat", "material \"sturdy\" {\n  like canvas\n  describes \"sturdy canvas\"\n}\n");
    test::write_text(world / "cloth/pinwale.hmat",
                     "material \"pinwale\" {\n  like corduroy\n  describes \"pinwale\"\n  grating period 1 mm\n}\n");
    test::write_text(world / "plain/rough.hmat", "material \"rough\" {\n  describes \"something rough\"\n  roughness 0.7\n}\n");
    test::write_text(lab / "library.toml", "id = \"lab\"\nname = \"lab\"\nversion = \"0.1.0\"\n");
    test::write_text(lab / "corduroy.hmat",
                     "material \"corduroy\" {\n  overrides\n  family cloth\n  describes \"our corduroy swatch\"\n"
                     "  like world:corduroy\n  roughness 0.6\n}\n");
    test::write_text(lab / "felt.hmat", "material \"felt\" {\n  like wide-wale\n  describes \"felt\"\n  grating period 5 mm\n}\n");
  }
  std::optional<catalog::CatalogReport> from_layers(std::optional<std::vector<fs::path>> changed = std::nullopt) const {
    catalog::CatalogOptions o;
    o.output = root / "from-layers";
    o.changed = std::move(changed);
    return catalog::write_catalog_from_layers({lab, world}, {}, "sim", o);
  }
  catalog::CatalogReport whole() const {
    compiler::CompileOptions opts;
    opts.library_path = {lab, world};
    catalog::CatalogOptions o;
    o.output = root / "whole";
    return catalog::write_catalog(compiler::Compiler(opts), o);
  }
  // Draws both; the layered one must equal the whole path's.
  catalog::CatalogReport both(std::optional<std::vector<fs::path>> changed = std::nullopt) const {
    const auto a = from_layers(std::move(changed));
    EXPECT_TRUE(a.has_value());
    if (!a) return {};
    EXPECT_TRUE(a->failures.empty()) << (a->failures.empty() ? "" : a->failures.front().diagnostics);
    const auto w = whole();
    EXPECT_TRUE(w.failures.empty());
    EXPECT_EQ(differing(pages_under(root / "from-layers"), pages_under(root / "whole")), std::vector<std::string>{});
    return *a;
  }
};

TEST(CatalogFromLayers, DrawsWhatAnEditChangesOverThePathAndEqualsTheCatalogOfTheWholePath) {
  const Path p("catalog-from-layers");
  auto a = p.both();
  EXPECT_EQ(a.entries, 7);  // the world's corduroy is hidden by the lab's
  EXPECT_EQ(a.rendered, 7);
  EXPECT_TRUE(fs::is_regular_file(curation::layer_index_path(p.lab)));
  EXPECT_TRUE(fs::is_regular_file(curation::layer_index_path(p.world)));
  EXPECT_TRUE(fs::is_regular_file(p.root / "from-layers/entries/pinwale.html"));
  EXPECT_EQ(pages_under(p.root / "from-layers").count("entries/corduroy.html"), 1u);

  // Nothing changed: nothing drawn.
  a = p.both();
  EXPECT_EQ(a.rendered, 0);
  EXPECT_EQ(a.reused, 7);

  // A lab entry nothing is built on: it alone, in place.
  replace_in(p.lab / "felt.hmat", "grating period 5 mm", "grating period 6 mm");
  a = p.both();
  EXPECT_EQ(a.rendered, 1);
  EXPECT_TRUE(a.in_place);
  // The record was compared with the path as it was: only the lab's entries, the world's rows its
  // update rewrote (none) and pinwale, which reaches the lab, are compared.
  EXPECT_EQ(a.compared, 3u);

  // The lab's corduroy: it, and the world's pinwale, which is built on `corduroy` and so, over the
  // path, on the lab's; the world's own index does not know that.
  replace_in(p.lab / "corduroy.hmat", "roughness 0.6", "roughness 0.65");
  a = p.both();
  EXPECT_EQ(a.rendered, 2);
  EXPECT_NE(pages_under(p.root / "from-layers").at("entries/pinwale.html").find("lab:corduroy"), std::string::npos);

  // A world entry: it, what the world builds on it, and every lab entry (a lab's index is redone
  // whenever a root below changes: docs/LIBRARY.md).
  replace_in(p.world / "cloth/canvas.hmat", "roughness 0.3", "roughness 0.35");
  a = p.both();
  EXPECT_EQ(a.rendered, 5);  // canvas, sturdy, lab:corduroy, felt, and pinwale, which is built on lab:corduroy
  EXPECT_EQ(a.compared, 5u);  // the same: the world's update rewrote canvas and sturdy

  // The world's reference: the bare roughness on it, and the lab's entries.
  replace_in(p.world / "cloth/reference-grating.hmat", "period 2.5 mm", "period 2.4 mm");
  a = p.both();
  EXPECT_EQ(a.rendered, 5);  // reference-grating, rough, lab:corduroy, felt, pinwale

  // A new lab entry hiding another world entry by name: the world's page goes, the lab's comes.
  test::write_text(p.lab / "canvas.hmat",
                   "material \"canvas\" {\n  overrides\n  describes \"our canvas\"\n  grating period 2 mm\n  roughness 0.45\n}\n");
  a = p.both();
  EXPECT_EQ(a.entries, 7);  // the lab's canvas in, the world's out
  EXPECT_EQ(a.compared, 7u);  // what the lab hides changed: every entry compared
  EXPECT_EQ(a.rendered, 2);  // canvas, and sturdy, which is `like canvas`: now the lab's
  EXPECT_NE(pages_under(p.root / "from-layers").at("entries/canvas.html").find("our canvas"), std::string::npos);
  EXPECT_NE(pages_under(p.root / "from-layers").at("entries/canvas.html").find("in front of <code>world:canvas</code>"),
            std::string::npos);

  // A new world entry that a lab entry now hides by name: the lab's page says so (a lab's entries
  // are drawn again whenever a root below changes; both() compares them with the whole path's).
  test::write_text(p.world / "cloth/felt.hmat",
                   "material \"felt\" {\n  describes \"the world's felt\"\n  grating period 4 mm\n  roughness 0.3\n}\n");
  a = p.both();
  EXPECT_NE(pages_under(p.root / "from-layers").at("entries/felt.html").find("in front of <code>world:felt</code>"),
            std::string::npos);
}

TEST(CatalogFromLayers, ToldWhichFilesChangedItDrawsWhatAWalkDraws) {
  const Path p("catalog-from-layers-changed");
  ASSERT_EQ(p.both().rendered, 7);
  // A lab file and a world file, both named: drawn as a walk would draw them.
  replace_in(p.lab / "felt.hmat", "grating period 5 mm", "grating period 6 mm");
  replace_in(p.world / "cloth/sturdy.hmat", "sturdy canvas", "sturdy cotton canvas");
  auto a = p.both(std::vector<fs::path>{p.lab / "felt.hmat", p.world / "cloth/sturdy.hmat"});
  EXPECT_EQ(a.rendered, 4);  // felt, sturdy, and the lab's corduroy and pinwale, as after any world edit
  // Only a lab file: the world's index is asked about nothing but the calibration and library.toml.
  replace_in(p.lab / "felt.hmat", "grating period 6 mm", "grating period 7 mm");
  EXPECT_EQ(p.both(std::vector<fs::path>{p.lab / "felt.hmat"}).rendered, 1);
  EXPECT_EQ(p.both().rendered, 0);  // a walk finds nothing more
  // A file of neither root nor the calibration is the caller's mistake.
  EXPECT_THROW(p.from_layers(std::vector<fs::path>{p.root / "elsewhere.hmat"}), std::invalid_argument);
}

TEST(CatalogFromLayers, AnEntryThatDoesNotCompileLeavesItToTheWholePath) {
  const Path p("catalog-from-layers-bad");
  ASSERT_TRUE(p.from_layers().has_value());
  replace_in(p.lab / "felt.hmat", "like wide-wale", "like canvass");
  // The lab's index does not build: the caller draws over the whole path, which names the entry.
  EXPECT_FALSE(p.from_layers().has_value());
  const auto w = p.whole();
  ASSERT_EQ(w.failures.size(), 1u);
  EXPECT_EQ(w.failures.front().name, "felt");
  // The lab's index, read over only what its entries reach below, is built again over the whole
  // path to say so: "did you mean" looks among every name, and canvas is one no lab entry reaches.
  std::ostringstream sink;
  curation::Progress quiet("indexing", 0, true, sink, false);
  curation::IndexOptions lab{p.lab, {}, curation::layer_index_path(p.lab), "sim"};
  lab.below = {p.world};
  const auto r = curation::build_index(lab, quiet);
  ASSERT_FALSE(r.ok);
  EXPECT_FALSE(r.part_of_path);
  EXPECT_NE(compiler::format_diagnostics(r.diagnostics).find("did you mean `canvas`?"), std::string::npos)
      << compiler::format_diagnostics(r.diagnostics);
}

TEST(CatalogFromLayers, ALabIndexReadsOnlyWhatItsEntriesReachBelowAndCompilesAsTheWholePathDoes) {
  const Path p("layered-root-part");
  // Built on the world's pinwale, which is `like corduroy`: over the path, the lab's corduroy.
  test::write_text(p.lab / "pinwale-swatch.hmat", "material \"pinwale-swatch\" {\n  like pinwale\n  describes \"our pinwale\"\n}\n");
  std::ostringstream sink;
  curation::Progress quiet("indexing", 0, true, sink, false);
  curation::IndexOptions world{p.world, {}, curation::layer_index_path(p.world), "sim"};
  ASSERT_TRUE(curation::build_index(world, quiet).ok);
  curation::IndexOptions lab{p.lab, {}, curation::layer_index_path(p.lab), "sim"};
  lab.below = {p.world};
  const auto part = curation::build_index(lab, quiet);
  ASSERT_TRUE(part.ok) << part.error;
  EXPECT_TRUE(part.part_of_path);
  EXPECT_EQ(part.entries, 3u);
  // Each lab row as the compiler over every file of the path compiles the entry.
  const auto rows_as_compiled = [&](const std::string& when) {
    compiler::CompileOptions opts;
    opts.library_path = {p.lab, p.world};
    const compiler::Compiler whole(opts);
    const curation::Index idx(curation::layer_index_path(p.lab));
    for (const auto* name : {"corduroy", "felt", "pinwale-swatch"}) {
      const auto r = whole.compile_file(p.lab / (std::string(name) + ".hmat"));
      ASSERT_TRUE(r.ok() && r.program) << name;
      const auto row = idx.entry(name);
      ASSERT_TRUE(row) << name;
      EXPECT_DOUBLE_EQ(row->max_lateral_force_N, r.program->max_lateral_force_N) << name << ", " << when;
      EXPECT_DOUBLE_EQ(row->roughness, r.program->roughness) << name << ", " << when;
      EXPECT_EQ(idx.provenance(name).size(), r.program->provenance.size()) << name << ", " << when;
    }
  };
  rows_as_compiled("first build");
  // The lab's corduroy changes what pinwale-swatch inherits through the world's pinwale: its row is redone.
  replace_in(p.lab / "corduroy.hmat", "roughness 0.6", "roughness 0.7");
  const auto again = curation::build_index(lab, quiet);
  ASSERT_TRUE(again.ok) << again.error;
  EXPECT_EQ(again.compiled, 2u);  // corduroy and pinwale-swatch
  rows_as_compiled("after the lab's corduroy changed");
}

}  // namespace
}  // namespace sandpaper
