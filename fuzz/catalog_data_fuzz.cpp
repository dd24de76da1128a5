// The catalog's data file (catalog-data.js, read back by an in-place update: catalog/index_page.hpp
// patch_index). Whatever the file holds, patching it never crashes or reads past it, and a patch it
// accepts is a fixed point: patching the result with the same rows gives the same text again.
// Rejection is nullopt (the whole file is then written), never an exception.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "sandpaper/catalog/index_page.hpp"
#include "sandpaper/compiler/library.hpp"

namespace {

// The library the corpus's catalogs were drawn from (tests/compiler/data/library-small).
const sandpaper::compiler::LibraryManifest& manifest() {
  static const auto m =
      sandpaper::compiler::Library(sandpaper::fuzz::source_dir() / "tests/compiler/data/library-small").manifest();
  return m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::string script(reinterpret_cast<const char*>(data), size);
  // Two rows as a run that redrew them would give: one that keeps its picture, one that loses it.
  catalog::IndexRow ref;
  ref.name = "ref";
  ref.family = "abrasives";
  ref.describes = "the reference grating </script> \\ '";
  ref.roughness = 0.5;
  ref.page = "entries/ref.html";
  ref.thumbnail = "entries/ref-thumb.png";
  catalog::IndexRow rib;
  rib.name = "rib";
  rib.family = "cloth";
  rib.aliases = {"ribbed-cloth"};
  rib.describes = "ribbed cloth";
  rib.page = "entries/rib.html";
  const std::vector<catalog::IndexRow> changed{ref, rib};
  const auto once = catalog::patch_index(script, manifest(), changed);
  if (!once) return 0;
  const auto twice = catalog::patch_index(once->script, manifest(), changed);
  fuzz::check(twice.has_value(), "a data file this patch wrote is refused by the next patch");
  fuzz::check(twice->script == once->script, "patching a patched data file with the same rows changed it");
  fuzz::check(twice->page == once->page, "patching a patched data file with the same rows changed the index page");
  return 0;
}
