// Layered libraries (issue 18; docs/LIBRARY.md, "Layered libraries"): a lab's own library on top of
// the world library; names resolve front to back, `like ID:NAME` names a root, and the provenance
// says which root every inherited number came from.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/library.hpp"
#include "test_support.hpp"

using namespace sandpaper;

namespace {

struct Layers {
  std::filesystem::path lab, world;
};

// world: corduroy (3 mm), reference-grating, gravel (a photograph in world/images); lab: its own
// corduroy built on the world's, and felt.
Layers make_layers(const std::string& tag) {
  const std::filesystem::path root = test::temp_dir(tag);
  Layers l{root / "lab", root / "world"};
  test::write_text(l.world / "library.toml",
      "id = \"world\"\nname = \"world\"\nversion = \"1.0.0\"\nreference = \"reference-grating\"\n"
      "[families.cloth]\ntitle = \"Cloth\"\n");
  test::write_text(l.world / "cloth/corduroy.hmat",
      "material \"corduroy\" {\n  family cloth\n  alias wide-wale\n  grating period 3 mm hill 60%\n  roughness 0.4\n}\n");
  test::write_text(l.world / "cloth/reference-grating.hmat", "material \"reference-grating\" {\n  grating period 2.5 mm\n  roughness 0.5\n}\n");
  test::write_text(l.world / "cloth/gravel.hmat",
      "material \"gravel\" {\n  heightmap \"../images/gravel.png\" size 95 mm smoothing 1 mm\n  roughness 0.6\n}\n");
  std::filesystem::create_directories(l.world / "images");
  std::filesystem::copy_file(std::filesystem::path(SANDPAPER_SOURCE_DIR) / "library/images/gravel.png", l.world / "images/gravel.png");
  test::write_text(l.lab / "library.toml", "id = \"lab\"\nname = \"lab\"\nversion = \"0.1.0\"\n");
  test::write_text(l.lab / "corduroy.hmat", "material \"corduroy\" {\n  overrides\n  like world:corduroy\n  roughness 0.6\n}\n");
  test::write_text(l.lab / "felt.hmat", "material \"felt\" {\n  like wide-wale\n  grating period 5 mm\n}\n");
  return l;
}

compiler::Compiler layered(const Layers& l) {
  compiler::CompileOptions o;
  o.library_path = {l.lab, l.world};
  return compiler::Compiler(o);
}

std::string provenance_of(const schema::PatchProgram& p, const std::string& parameter) {
  for (const auto& r : p.provenance)
    if (r.parameter == parameter) return r.source;
  return "(none)";
}

}  // namespace

TEST(LayeredLibrary, ANameIsTheFrontRootsAndIdColonNameIsThatRootsOwn) {
  const auto l = make_layers("layers-names");
  const auto c = layered(l);
  const auto& lib = c.library();
  ASSERT_EQ(lib.roots().size(), 2u);
  EXPECT_EQ(lib.roots()[0].id, "lab");
  EXPECT_EQ(lib.roots()[1].id, "world");
  EXPECT_EQ(lib.entry("corduroy")->root, 0u);
  EXPECT_EQ(lib.entry("world:corduroy")->root, 1u);
  EXPECT_EQ(lib.entry("lab:corduroy")->root, 0u);
  EXPECT_EQ(lib.entry("world:wide-wale")->name, "corduroy");  // aliases work qualified too
  EXPECT_EQ(lib.entry("lab:gravel"), nullptr);                // a root holds only its own entries
  EXPECT_EQ(lib.entry("nowhere:corduroy"), nullptr);
  EXPECT_EQ(lib.shadowed_by(*lib.entry("corduroy")), lib.entry("world:corduroy"));
  EXPECT_EQ(lib.shadowed_by(*lib.entry("felt")), nullptr);
  EXPECT_TRUE(lib.entry("corduroy")->overrides);
  EXPECT_EQ(lib.manifest().reference, "reference-grating");  // the first root that declares one
  EXPECT_EQ(lib.manifest().name, "lab");

  // The lab's corduroy builds on the world's (not a `like` cycle, though both are named corduroy).
  const auto lab = c.compile_text("corduroy");
  ASSERT_TRUE(lab.ok()) << compiler::format_diagnostics(lab.diagnostics);
  const auto world = c.compile_text("world:corduroy");
  ASSERT_TRUE(world.ok()) << compiler::format_diagnostics(world.diagnostics);
  EXPECT_NEAR(lab.material->roughness->si, 0.6, 1e-12);
  EXPECT_NEAR(world.material->roughness->si, 0.4, 1e-12);
  EXPECT_GT(lab.program->max_lateral_force_N, world.program->max_lateral_force_N);

  const auto unknown = c.compile_text("like nowhere:corduroy");
  EXPECT_TRUE(unknown.diagnostics.has_errors());
  EXPECT_EQ(unknown.diagnostics.all().front().code, "E0301");
}

TEST(LayeredLibrary, ProvenanceSaysWhichRootEveryInheritedNumberCameFrom) {
  const auto l = make_layers("layers-provenance");
  const auto c = layered(l);
  const auto r = c.compile_text("like corduroy");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  // The period was said in the world's corduroy, the roughness in the lab's.
  EXPECT_NE(provenance_of(*r.program, "texture.period").find("library/world/cloth/corduroy.hmat:4"), std::string::npos)
      << provenance_of(*r.program, "texture.period");
  EXPECT_NE(provenance_of(*r.program, "texture.roughness_target").find("library lab:corduroy (library/lab/corduroy.hmat:4"),
            std::string::npos)
      << provenance_of(*r.program, "texture.roughness_target");
  // A bare perceptual description starts from the reference, which only the world has.
  const auto bare = c.compile_text("roughness 0.3");
  ASSERT_TRUE(bare.ok()) << compiler::format_diagnostics(bare.diagnostics);
  EXPECT_NE(provenance_of(*bare.program, "texture.period").find("library/world/cloth/reference-grating.hmat:2"), std::string::npos)
      << provenance_of(*bare.program, "texture.period");
}

TEST(LayeredLibrary, ImagesResolveInsideTheirOwnRootAndCyclesAreStillFound) {
  const auto l = make_layers("layers-images");
  test::write_text(l.lab / "loop.hmat", "material \"loop\" {\n  like loop\n}\n");
  const auto c = layered(l);
  const auto g = c.compile_text("like gravel");
  ASSERT_TRUE(g.ok()) << compiler::format_diagnostics(g.diagnostics);
  EXPECT_EQ(g.program->terms.size(), 1u);
  const auto loop = c.compile_text("like loop");
  ASSERT_TRUE(loop.diagnostics.has_errors());
  EXPECT_NE(compiler::format_diagnostics(loop.diagnostics).find("'lab:loop' (as 'loop') is built on itself"), std::string::npos)
      << compiler::format_diagnostics(loop.diagnostics);
  // The same folders as one root each: felt's `like wide-wale` is unknown without the world.
  compiler::CompileOptions lab_only;
  lab_only.library_dir = l.lab;
  EXPECT_TRUE(compiler::Compiler(lab_only).compile_text("like felt").diagnostics.has_errors());
  EXPECT_TRUE(c.compile_text("like felt").ok());
}

TEST(LayeredLibrary, TheLexerJoinsIdColonNameAndTheEnvironmentGivesThePath) {
  compiler::Diagnostics d;
  auto file = std::make_shared<const compiler::SourceFile>("t.hmat", "like world:corduroy\nroughness: 0.5\n");
  const auto toks = compiler::lex(file, d);
  std::vector<std::string> words;
  for (const auto& t : toks)
    if (t.kind == compiler::TokenKind::Word) words.push_back(t.text);
  // A ':' between word characters joins; one not followed by a word stays out of the word.
  EXPECT_EQ(words, (std::vector<std::string>{"like", "world:corduroy", "roughness"}));

  EXPECT_EQ(compiler::split_library_path("a:b::c"), (std::vector<std::filesystem::path>{"a", "b", "c"}));
  const char* old = std::getenv("SANDPAPER_LIBRARY_PATH");
  const std::string saved = old ? old : "";
  ::setenv("SANDPAPER_LIBRARY_PATH", "/lab:/world", 1);
  EXPECT_EQ(compiler::default_library_path(), (std::vector<std::filesystem::path>{"/lab", "/world"}));
  if (old) ::setenv("SANDPAPER_LIBRARY_PATH", saved.c_str(), 1);
  else ::unsetenv("SANDPAPER_LIBRARY_PATH");
}
