// write_catalog_from_index: a catalog drawn from the library's index, reading only the entries it
// draws, must be the catalog of the whole library, byte for byte.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>

#include "sandpaper/catalog/catalog.hpp"
#include "sandpaper/curation/index.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {
namespace fs = std::filesystem;
using test::replace_in;

// The record's rows and settings, one line each. Not its bytes: drawn from an index, the record also
// names the index's fingerprint, which a catalog drawn without one has not.
std::string record_rows(const fs::path& file) {
  sqlite3* db = nullptr;
  std::string out;
  if (sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
    sqlite3_exec(
        db, "SELECT 'settings', value FROM meta WHERE key = 'settings' UNION ALL SELECT * FROM (SELECT * FROM entries ORDER BY name)",
        [](void* o, int n, char** v, char**) {
          for (int i = 0; i < n; ++i) *static_cast<std::string*>(o) += std::string(v[i] ? v[i] : "NULL") + "|";
          *static_cast<std::string*>(o) += "\n";
          return 0;
        },
        &out, nullptr);
  }
  sqlite3_close(db);
  return out;
}

std::string recorded_fingerprint(const fs::path& file) {
  sqlite3* db = nullptr;
  std::string out;
  if (sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK)
    sqlite3_exec(
        db, "SELECT value FROM meta WHERE key = 'index_fingerprint'",
        [](void* o, int, char** v, char**) {
          *static_cast<std::string*>(o) = v[0] ? v[0] : "";
          return 0;
        },
        &out, nullptr);
  sqlite3_close(db);
  return out;
}

std::map<std::string, std::string> files_under(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) {
      const auto rel = fs::relative(e.path(), dir).generic_string();
      if (rel == "inputs.sqlite") {
        out[rel] = record_rows(e.path());
        continue;
      }
      std::ifstream in(e.path(), std::ios::binary);
      out[rel] = std::string(std::istreambuf_iterator<char>(in), {});
    }
  return out;
}

// A copy of the small test library, its catalog drawn from its index into root/from-index (told
// `changed` if given), and from a compiler over the whole library (no index) into `out`.
struct SmallLibrary {
  fs::path root, lib;
  explicit SmallLibrary(const std::string& name) : root(test::temp_dir(name)), lib(root / "lib") {
    fs::copy(SANDPAPER_SOURCE_DIR "/tests/compiler/data/library-small", lib, fs::copy_options::recursive);
  }
  std::optional<catalog::CatalogReport> from_index(std::optional<std::vector<fs::path>> changed = std::nullopt) const {
    catalog::CatalogOptions o;
    o.output = root / "from-index";
    o.changed = std::move(changed);
    return catalog::write_catalog_from_index(lib, {}, "sim", o);
  }
  catalog::CatalogReport whole(const std::string& out = "whole") const {
    compiler::CompileOptions opts;
    opts.library_dir = lib;
    catalog::CatalogOptions o;
    o.output = root / out;
    return catalog::write_catalog(compiler::Compiler(opts), o);
  }
};

TEST(CatalogFromIndex, DrawsOnlyWhatChangedAndEqualsTheCatalogOfTheWholeLibrary) {
  const SmallLibrary small("catalog-from-index");
  const auto& [root, lib] = std::tie(small.root, small.lib);
  const auto from_index = [&](std::optional<std::vector<fs::path>> changed = std::nullopt) { return small.from_index(std::move(changed)); };
  const auto whole = [&] { return small.whole(); };
  auto a = from_index();
  ASSERT_TRUE(a.has_value());
  ASSERT_TRUE(a->failures.empty());
  EXPECT_EQ(a->rendered, 4);
  EXPECT_TRUE(fs::is_regular_file(curation::default_index_path(lib)));
  ASSERT_TRUE(whole().failures.empty());
  EXPECT_EQ(files_under(root / "from-index"), files_under(root / "whole"));

  // An entry others are built on: it and they are drawn, from a library of just what they reach.
  replace_in(lib / "cloth/rib.hmat", "roughness 0.4", "roughness 0.45");
  a = from_index();
  ASSERT_TRUE(a.has_value());
  const auto w = whole();
  EXPECT_GE(a->rendered, 2);
  EXPECT_EQ(a->rendered, w.rendered);
  EXPECT_EQ(a->reused, w.reused);
  EXPECT_EQ(files_under(root / "from-index"), files_under(root / "whole"));
  // An entry built on one that did not change: drawn with what it is built on read too.
  replace_in(lib / "cloth/fine-rib.hmat", "describes \"", "describes \"(renamed) ");
  a = from_index();
  ASSERT_TRUE(a.has_value());
  ASSERT_TRUE(a->failures.empty()) << a->failures.front().diagnostics;
  EXPECT_EQ(a->rendered, 1);
  ASSERT_TRUE(whole().failures.empty());
  EXPECT_EQ(files_under(root / "from-index"), files_under(root / "whole"));
  // Nothing changed: nothing drawn.
  a = from_index();
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->rendered, 0);
  EXPECT_EQ(a->reused, 4);

  // Another device: its inputs are not the index's, so the whole library is read.
  catalog::CatalogOptions o;
  o.output = root / "other-device";
  EXPECT_FALSE(catalog::write_catalog_from_index(lib, {}, "sandpaper-1995", o).has_value());
  // An entry that does not compile: the index does not build, and nothing is written here.
  replace_in(lib / "ref.hmat", "roughness", "roughnes");
  o.output = root / "from-index";
  const auto before = files_under(root / "from-index");
  EXPECT_FALSE(catalog::write_catalog_from_index(lib, {}, "sim", o).has_value());
  EXPECT_EQ(files_under(root / "from-index"), before);
}

// After an in-place index update, a catalog whose record was compared with the index as it was
// compares only the entries the update rewrote; one whose record was not (the index brought up to
// date by `library index` in between) compares every entry, and so still draws what changed.
TEST(CatalogFromIndex, ComparesOnlyTheRewrittenEntriesWhenItsRecordMatchedTheIndexBeforeTheUpdate) {
  const SmallLibrary small("catalog-from-index-partial");
  const auto& [root, lib] = std::tie(small.root, small.lib);
  const auto from_index = [&](std::optional<std::vector<fs::path>> changed = std::nullopt) { return small.from_index(std::move(changed)); };
  const auto whole = [&] { return small.whole(); };
  auto a = from_index();
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->compared, 4u);
  const fs::path record = root / "from-index" / "inputs.sqlite";
  const auto index_fingerprint = [&] { return curation::Index(curation::default_index_path(lib)).meta("fingerprint"); };
  EXPECT_EQ(recorded_fingerprint(record), index_fingerprint());

  // An entry nothing is built on: the update rewrites its row alone, and the catalog compares it alone.
  replace_in(lib / "cloth/fine-rib.hmat", "describes \"", "describes \"(one) ");
  a = from_index();
  ASSERT_TRUE(a.has_value());
  ASSERT_TRUE(a->failures.empty()) << a->failures.front().diagnostics;
  EXPECT_EQ(a->compared, 1u);
  EXPECT_EQ(a->rendered, 1);
  EXPECT_EQ(a->reused, 3);
  EXPECT_EQ(a->entries, 4);
  EXPECT_TRUE(a->in_place);
  EXPECT_EQ(recorded_fingerprint(record), index_fingerprint());
  ASSERT_TRUE(whole().failures.empty());
  EXPECT_EQ(files_under(root / "from-index"), files_under(root / "whole"));
  // The same, told which file changed.
  replace_in(lib / "cloth/fine-rib.hmat", "describes \"", "describes \"(two) ");
  a = from_index(std::vector<fs::path>{lib / "cloth/fine-rib.hmat"});
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->compared, 1u);
  EXPECT_EQ(a->rendered, 1);
  ASSERT_TRUE(whole().failures.empty());
  EXPECT_EQ(files_under(root / "from-index"), files_under(root / "whole"));

  // A family the data file has not: it is written whole, from the record's rows in the index's order.
  replace_in(lib / "cloth/fine-rib.hmat", "family cloth", "family wool");
  a = from_index();
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->compared, 1u);
  EXPECT_EQ(a->rendered, 1);
  ASSERT_TRUE(whole().failures.empty());
  EXPECT_EQ(files_under(root / "from-index"), files_under(root / "whole"));

  // The index updated by `library index` alone: the catalog's update rewrites no row, but the
  // record was compared with an older index, so every entry is compared and rib's change is drawn.
  replace_in(lib / "cloth/rib.hmat", "roughness 0.4", "roughness 0.45");
  std::ostringstream sink;
  curation::Progress quiet("indexing", 0, true, sink, false);
  ASSERT_TRUE(curation::build_index(curation::IndexOptions{lib, {}, curation::default_index_path(lib), "sim"}, quiet).ok);
  a = from_index();
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->compared, 4u);
  EXPECT_GE(a->rendered, 2);  // rib and what is built on it
  ASSERT_TRUE(whole().failures.empty());
  EXPECT_EQ(files_under(root / "from-index"), files_under(root / "whole"));
  // Nothing changed since: nothing compared, nothing drawn.
  a = from_index();
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->compared, 0u);
  EXPECT_EQ(a->rendered, 0);
  EXPECT_EQ(a->reused, 4);

  // A catalog drawn without the index clears the recorded fingerprint: the next one compares all.
  ASSERT_TRUE(small.whole("from-index").failures.empty());
  EXPECT_EQ(recorded_fingerprint(record), "");
  a = from_index();
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->compared, 4u);
  EXPECT_EQ(a->rendered, 0);
  EXPECT_EQ(recorded_fingerprint(record), index_fingerprint());  // written though nothing was drawn
  a = from_index();
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->compared, 0u);
}

}  // namespace
}  // namespace sandpaper
