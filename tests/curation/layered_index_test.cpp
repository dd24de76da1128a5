// Indexes and queries over a layered library path (issue 18; docs/LIBRARY.md, "Layered
// libraries"): every root has its own index built over the roots below it; queries see what the
// compiler sees (the front root's entry for a name), and a change below redoes the root in front.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/layers.hpp"
#include "test_support.hpp"

namespace sandpaper::test {
namespace {

using namespace sandpaper::curation;

struct Layers {
  std::filesystem::path lab, world;
};

// world: corduroy (3 mm, alias wide-wale), reference-grating, canvas; lab: its own corduroy built
// on the world's (hiding it), and felt built on wide-wale (the world's corduroy, by its alias).
Layers make_layers(const std::string& tag) {
  const std::filesystem::path root = temp_dir(tag);
  Layers l{root / "lab", root / "world"};
  write_text(l.world / "library.toml",
      "id = \"world\"\nname = \"world\"\nversion = \"1.0.0\"\nreference = \"reference-grating\"\n"
      "[families.cloth]\ntitle = \"Cloth\"\n");
  write_text(l.world / "cloth/corduroy.hmat",
      "material \"corduroy\" {\n  family cloth\n  alias wide-wale\n  describes \"wide-wale corduroy\"\n"
      "  grating period 3 mm hill 60%\n  roughness 0.4\n}\n");
  write_text(l.world / "cloth/reference-grating.hmat", "material \"reference-grating\" {\n  grating period 2.5 mm\n  roughness 0.5\n}\n");
  write_text(l.world / "cloth/canvas.hmat", "material \"canvas\" {\n  family cloth\n  describes \"canvas\"\n  grating period 1.5 mm\n  roughness 0.3\n}\n");
  write_text(l.lab / "library.toml", "id = \"lab\"\nname = \"lab\"\nversion = \"0.1.0\"\n");
  write_text(l.lab / "corduroy.hmat",
      "material \"corduroy\" {\n  overrides\n  family cloth\n  describes \"our corduroy swatch\"\n  like world:corduroy\n  roughness 0.6\n}\n");
  write_text(l.lab / "felt.hmat", "material \"felt\" {\n  like wide-wale\n  grating period 5 mm\n}\n");
  return l;
}

IndexBuildResult build(const std::filesystem::path& root, const std::vector<std::filesystem::path>& below) {
  std::ostringstream sink;
  Progress quiet("indexing", 0, true, sink, false);
  IndexOptions o{root, {}, layer_index_path(root), "sim"};
  o.below = below;
  return build_index(o, quiet);
}

IndexState state(const std::filesystem::path& root, const std::vector<std::filesystem::path>& below) {
  return index_state(layer_index_path(root), root, calibration::default_calibration_dir(), below);
}

std::string provenance_source(const Index& idx, const std::string& name, const std::string& parameter) {
  for (const auto& p : idx.provenance(name))
    if (p.parameter == parameter) return p.source;
  return "(none)";
}

TEST(LayeredIndex, EachRootIsIndexedOverTheRootsBelowAndQueriesSeeWhatTheCompilerSees) {
  const auto l = make_layers("layered-index-queries");
  ASSERT_TRUE(build(l.world, {}).ok);
  const auto lab = build(l.lab, {l.world});
  ASSERT_TRUE(lab.ok) << lab.error;
  EXPECT_EQ(lab.entries, 2u);  // the lab's own entries; the world's are in the world's index

  const LayeredIndex idx({l.lab, l.world});
  ASSERT_EQ(idx.size(), 2u);
  EXPECT_EQ(idx.id(0), "lab");
  EXPECT_EQ(idx.id(1), "world");
  using Found = std::optional<std::pair<std::size_t, std::string>>;
  EXPECT_EQ(idx.resolve("corduroy"), Found({0, "corduroy"}));
  EXPECT_EQ(idx.resolve("world:corduroy"), Found({1, "corduroy"}));
  EXPECT_EQ(idx.resolve("wide-wale"), Found({1, "corduroy"}));  // no root in front has the alias
  EXPECT_EQ(idx.resolve("lab:canvas"), std::nullopt);
  EXPECT_TRUE(idx.hidden(1, "corduroy"));
  EXPECT_FALSE(idx.hidden(1, "canvas"));

  // Provenance across roots: the lab's corduroy takes its period from the world's file.
  EXPECT_NE(provenance_source(idx.index(0), "corduroy", "texture.period").find("world:corduroy"), std::string::npos)
      << provenance_source(idx.index(0), "corduroy", "texture.period");
  EXPECT_NE(provenance_source(idx.index(0), "corduroy", "texture.period").find("library/world/cloth/corduroy.hmat"), std::string::npos);
  EXPECT_NEAR(idx.entry(0, "felt")->period_m, 0.005, 1e-12);

  // search: the front root's corduroy, never the one it hides; the hidden one by its alias.
  SearchQuery q;
  q.words = {"corduroy"};
  const auto hits = idx.search(q);
  ASSERT_FALSE(hits.empty());
  EXPECT_EQ(hits.front().entry.name, "corduroy");
  EXPECT_EQ(hits.front().entry.root, "lab");
  for (const auto& h : hits) EXPECT_FALSE(h.entry.root == "world" && h.entry.name == "corduroy") << h.why;
  q.words = {"wide-wale"};
  const auto by_alias = idx.search(q);
  ASSERT_FALSE(by_alias.empty());
  EXPECT_EQ(by_alias.front().entry.root, "world");
  EXPECT_EQ(by_alias.front().why, "alias");
  q.words = {};
  q.family = "cloth";
  std::vector<std::string> cloth;
  for (const auto& h : idx.search(q)) cloth.push_back(h.entry.root + ":" + h.entry.name);
  std::sort(cloth.begin(), cloth.end());
  EXPECT_EQ(cloth, (std::vector<std::string>{"lab:corduroy", "world:canvas"}));

  // near: entries of every root, the hidden one left out.
  const auto near = idx.nearest(0, "felt", 10);
  std::vector<std::string> seen;
  for (const auto& n : near) seen.push_back(n.entry.root + ":" + n.entry.name);
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(seen, (std::vector<std::string>{"lab:corduroy", "world:canvas", "world:reference-grating"}));
}

TEST(LayeredIndex, AChangeInARootBelowMakesTheRootInFrontStaleAndRedoesItsEntries) {
  const auto l = make_layers("layered-index-stale");
  ASSERT_TRUE(build(l.world, {}).ok);
  ASSERT_TRUE(build(l.lab, {l.world}).ok);
  EXPECT_EQ(state(l.lab, {l.world}), IndexState::Fresh);
  EXPECT_EQ(state(l.lab, {}), IndexState::Stale);  // built over the world: not an index of the lab alone

  // Unchanged: nothing compiled again.
  auto again = build(l.lab, {l.world});
  ASSERT_TRUE(again.ok);
  EXPECT_EQ(again.compiled, 0u);
  EXPECT_EQ(again.reused, 2u);

  // The world's corduroy gets wider ribs: the lab's corduroy and felt inherit them.
  write_text(l.world / "cloth/corduroy.hmat",
      "material \"corduroy\" {\n  family cloth\n  alias wide-wale\n  describes \"wide-wale corduroy\"\n"
      "  grating period 4 mm hill 60%\n  roughness 0.4\n}\n");
  // As an editor saving by rename would: the folder's time moves (the cheap staleness check reads folders).
  std::filesystem::last_write_time(l.world / "cloth", std::filesystem::file_time_type::clock::now() + std::chrono::seconds(2));
  EXPECT_EQ(state(l.lab, {l.world}), IndexState::Stale);
  const auto refused = build(l.lab, {l.world});  // the world's index is stale: build from the bottom up
  EXPECT_FALSE(refused.ok);
  EXPECT_NE(refused.error.find("bottom up"), std::string::npos) << refused.error;
  ASSERT_TRUE(build(l.world, {}).ok);
  EXPECT_EQ(state(l.lab, {l.world}), IndexState::Stale);  // the world's fingerprint changed
  const auto redone = build(l.lab, {l.world});
  ASSERT_TRUE(redone.ok) << redone.error;
  EXPECT_EQ(redone.compiled, 2u);
  EXPECT_EQ(state(l.lab, {l.world}), IndexState::Fresh);
  const LayeredIndex idx({l.lab, l.world});
  EXPECT_NEAR(idx.entry(0, "corduroy")->period_m, 0.004, 1e-12);
}

}  // namespace
}  // namespace sandpaper::test
