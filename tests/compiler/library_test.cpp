// The library as data: metadata statements, aliases, families, deprecation, the manifest and the
// reference texture for bare perceptual descriptions (issue 6; schema/LANGUAGE.md "Library entries").
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/library.hpp"
#include "sandpaper/compiler/parser.hpp"
#include "test_support.hpp"

using namespace sandpaper;

namespace {

const std::string kSmall = SANDPAPER_SOURCE_DIR "/tests/compiler/data/library-small";

compiler::CompileOptions small_options() {
  compiler::CompileOptions o;
  o.library_dir = kSmall;
  return o;
}

compiler::MaterialSyntax parse_text(const std::string& text, compiler::Diagnostics& d) {
  auto file = std::make_shared<const compiler::SourceFile>("t.hmat", text);
  auto toks = compiler::lex(file, d);
  return compiler::parse(toks, file, d);
}

std::vector<std::string> diag_codes(const compiler::Diagnostics& d) {
  std::vector<std::string> out;
  for (const auto& x : d.all()) out.push_back(x.code);
  return out;
}

}  // namespace

TEST(LibraryMetadata, SourcesAttachToTheStatementBeforeThem) {
  compiler::Diagnostics d;
  auto syn = parse_text(
      "material \"x\" {\n  family cloth\n  alias x2\n  licence \"CC0-1.0\"\n  grating period 2 mm\n"
      "  source standard \"ISO 1\"\n  source by-ear \"hill\"\n  roughness 0.5\n  source derived \"2 x 0.25\"\n}\n",
      d);
  ASSERT_FALSE(d.has_errors()) << compiler::format_diagnostics(d);
  ASSERT_EQ(syn.statements.size(), 5u);
  EXPECT_EQ(syn.statements[3].sources.size(), 2u);
  EXPECT_EQ(syn.statements[3].sources[0].kind, compiler::SourceKind::Standard);
  EXPECT_EQ(syn.statements[3].sources[1].text, "hill");
  EXPECT_EQ(syn.statements[4].sources.size(), 1u);
  EXPECT_EQ(syn.statements[4].sources[0].location.line, 9);
  EXPECT_TRUE(compiler::is_metadata(syn.statements[0]));
  EXPECT_FALSE(compiler::carries_numbers(syn.statements[2]));  // licence
  EXPECT_TRUE(compiler::carries_numbers(syn.statements[3]));   // grating
  EXPECT_STREQ(compiler::source_kind_phrase(compiler::SourceKind::ByEar), "designed by ear");
}

TEST(LibraryMetadata, BadSourcesAreErrorsThatSayHowToWriteThem) {
  compiler::Diagnostics d;
  parse_text("source by-ear \"nothing before\"\ngrating period 2 mm amplitude 1 N\nsource guess \"x\"\n"
             "roughness 0.3\nsource publicaton \"Minsky 1995\"\n",
             d);
  EXPECT_EQ(diag_codes(d), (std::vector<std::string>{"E0212", "E0213", "E0213"}));
  EXPECT_EQ(d.all()[1].location.line, 3);
  EXPECT_NE(d.all()[1].suggestion.find("by-ear"), std::string::npos) << d.all()[1].suggestion;
  EXPECT_EQ(d.all()[2].suggestion, "did you mean `publication`?");
}

TEST(LibraryMetadata, MetadataIsNotInheritedAndFamilyIsSetOnce) {
  compiler::Compiler c(small_options());
  auto r = c.compile_text("like fine-rib");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_TRUE(r.material->family.empty());
  EXPECT_TRUE(r.material->licence.empty());
  auto twice = c.compile_text("family cloth; family abrasives; grating period 2 mm amplitude 1 N");
  EXPECT_EQ(test::codes(twice), std::vector<std::string>{"E0302"});
}

TEST(Library, ScansFamiliesInSubfoldersAndReadsTheManifest) {
  compiler::Library lib(kSmall);
  EXPECT_EQ(lib.names(), (std::vector<std::string>{"fine-rib", "old-rib", "ref", "rib"}));
  EXPECT_FALSE(lib.scan_diagnostics().has_errors()) << compiler::format_diagnostics(lib.scan_diagnostics());
  EXPECT_EQ(lib.manifest().version, "0.3.1");
  EXPECT_EQ(lib.manifest().reference, "ref");
  ASSERT_EQ(lib.manifest().families.size(), 2u);
  EXPECT_EQ(lib.manifest().families[0].id, "cloth");  // the file's order, not alphabetical
  EXPECT_FALSE(lib.manifest().families[0].stimulus_set);
  EXPECT_TRUE(lib.manifest().families[1].stimulus_set);
  const auto* rib = lib.entry("ribbed-cloth");
  ASSERT_NE(rib, nullptr);
  EXPECT_EQ(rib->name, "rib");
  EXPECT_EQ(rib->relative_path, "cloth/rib.hmat");
  EXPECT_EQ(rib->aliases, (std::vector<std::string>{"ribbed-cloth", "rib2"}));
  EXPECT_EQ(rib->family, "cloth");
  EXPECT_EQ(lib.entry("fine-rib")->licence, "CC-BY-4.0");
  EXPECT_EQ(lib.entry("fine-rib")->likes, std::vector<std::string>{"ribbed-cloth"});
  EXPECT_EQ(lib.entry("old-rib")->deprecated_by, "rib");
  EXPECT_FALSE(lib.find("nothing-here"));
}

TEST(Library, LikeFindsAnEntryByAliasAndNamesItCanonically) {
  compiler::Compiler c(small_options());
  auto r = c.compile_text("like rib2; roughness 0.3");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_EQ(r.material->like_chain, std::vector<std::string>{"rib"});
  EXPECT_EQ(r.material->like_origins, std::vector<std::string>{"library/cloth/rib.hmat"});
  EXPECT_NEAR(std::get<compiler::ResolvedGrating>(r.material->texture).period.si, 0.003, 1e-12);
}

TEST(Library, DeprecatedEntryWarnsAndNamesItsReplacement) {
  compiler::Compiler c(small_options());
  auto r = c.compile_text("old-rib");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  auto w = test::codes(r, compiler::Severity::Warning);
  ASSERT_EQ(std::count(w.begin(), w.end(), "W0340"), 1);
  for (const auto& d : r.diagnostics.all())
    if (d.code == "W0340") {
      EXPECT_NE(d.message.find("use 'rib'"), std::string::npos) << d.message;
      EXPECT_EQ(d.suggestion.rfind("write like rib", 0), 0u) << d.suggestion;
    }
  EXPECT_TRUE(test::codes(c.compile_text("rib"), compiler::Severity::Warning).empty());
}

TEST(Library, BarePerceptualDescriptionStartsFromTheReferenceTexture) {
  compiler::Compiler c(small_options());
  auto r = c.compile_text("roughness 0.6");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_EQ(r.material->like_chain, std::vector<std::string>{"ref"});
  EXPECT_NEAR(r.program->max_lateral_force_N, test::expected_force_for_roughness(0.6), 1e-9);
  const auto& period = std::get<compiler::ResolvedGrating>(r.material->texture).period;
  EXPECT_NEAR(period.si, 0.0025, 1e-12);
  EXPECT_NE(period.source.find("reference texture"), std::string::npos) << period.source;
  // It says it is felt on the reference texture, not that it is the reference texture.
  EXPECT_EQ(r.material->describes.rfind("felt on the library's reference texture, ref", 0), 0u) << r.material->describes;
  EXPECT_EQ(r.program->describes, r.material->describes);
  // A texture of its own, or a `like`, is not replaced.
  auto own = c.compile_text("grating period 4 mm; roughness 0.6");
  ASSERT_TRUE(own.ok());
  EXPECT_TRUE(own.material->like_chain.empty());
  // The shipped library names one too: application code asks for "roughness 0.6" by itself.
  auto shipped = test::shipped_compiler().compile_text("roughness coarse");
  ASSERT_TRUE(shipped.ok()) << compiler::format_diagnostics(shipped.diagnostics);
  EXPECT_EQ(shipped.material->like_chain.size(), 1u);
}

TEST(Library, LikeCyclesThroughAliasesAreFound) {
  auto dir = test::temp_dir("library-cycle");
  auto write = [&](const std::string& name, const std::string& body) {
    std::ofstream(dir + "/" + name + ".hmat") << body;
  };
  write("a", "material \"a\" {\n  alias first\n  like second\n}\n");
  write("b", "material \"b\" {\n  alias second\n  like first\n}\n");
  compiler::CompileOptions o;
  o.library_dir = dir;
  compiler::Compiler c(o);
  auto r = c.compile_text("a");
  ASSERT_FALSE(r.ok());
  std::string all = compiler::format_diagnostics(r.diagnostics);
  // Found on entry names, though written with aliases.
  EXPECT_NE(all.find("library entry 'a' (as 'first') is built on itself"), std::string::npos) << all;
}

// An entry file named in Latin-1 (`caf\xe9.hmat`): its name can never be written in a `like` (material
// text is UTF-8), and `library catalog` stopped at it with nlohmann's raw type_error 316, exit 2
// (docs/RELIABILITY.md, F30). It is reported (E0614, the path shown with U+FFFD) and not read.
TEST(Library, AnEntryWhosePathIsNotUtf8IsReportedAndNotRead) {
  const std::filesystem::path dir = test::temp_dir("library-latin1");
  std::filesystem::copy(kSmall, dir, std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing);
  std::filesystem::copy_file(dir / "cloth" / "rib.hmat", dir / "cloth" / "caf\xe9.hmat");
  const compiler::Library lib(dir);
  EXPECT_EQ(lib.names(), (std::vector<std::string>{"fine-rib", "old-rib", "ref", "rib"}));
  ASSERT_EQ(diag_codes(lib.scan_diagnostics()), std::vector<std::string>{"E0614"});
  const auto& d = lib.scan_diagnostics().all().front();
  EXPECT_EQ(d.location.file->name, "library/cloth/caf\xef\xbf\xbd.hmat");
  EXPECT_NE(d.message.find("not UTF-8 (byte 10)"), std::string::npos) << d.message;
  std::filesystem::remove_all(dir);
}
