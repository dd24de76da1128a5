// write_catalog_from_index: a catalog drawn from the library's index, reading only the entries it
// draws, must be the catalog of the whole library, byte for byte.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include "sandpaper/catalog/catalog.hpp"
#include "sandpaper/curation/index.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {
namespace fs = std::filesystem;

std::map<std::string, std::string> files_under(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) {
      std::ifstream in(e.path(), std::ios::binary);
      out[fs::relative(e.path(), dir).generic_string()] = std::string(std::istreambuf_iterator<char>(in), {});
    }
  return out;
}

void replace_in(const fs::path& file, const std::string& from, const std::string& to) {
  std::ifstream in(file, std::ios::binary);
  std::string text(std::istreambuf_iterator<char>(in), {});
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from << " not in " << file;
  text.replace(at, from.size(), to);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
}

TEST(CatalogFromIndex, DrawsOnlyWhatChangedAndEqualsTheCatalogOfTheWholeLibrary) {
  const fs::path root = test::temp_dir("catalog-from-index");
  const fs::path lib = root / "lib";
  fs::copy(SANDPAPER_SOURCE_DIR "/tests/compiler/data/library-small", lib, fs::copy_options::recursive);
  const auto from_index = [&] {
    catalog::CatalogOptions o;
    o.output = root / "from-index";
    return catalog::write_catalog_from_index(lib, {}, "sim", o);
  };
  const auto whole = [&] {
    compiler::CompileOptions opts;
    opts.library_dir = lib;
    catalog::CatalogOptions o;
    o.output = root / "whole";
    return catalog::write_catalog(compiler::Compiler(opts), o);
  };
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

}  // namespace
}  // namespace sandpaper
