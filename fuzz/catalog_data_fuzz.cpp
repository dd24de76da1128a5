// The catalog index's data files (catalog-data.js and its parts catalog-data/part-NNNNN.js, read back
// by an in-place update: catalog/index_page.hpp patch_index). The input is the head file, then each
// part in order, separated by lines "//--". Whatever the files hold, patching them never crashes or
// reads past them, and a patch it accepts is a fixed point: patching its result with the same rows
// gives the same files again. Rejection is nullopt (the files are then written whole), never an
// exception.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
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

// The input's files by path: the head, then part 0, 1, ... between separator lines.
std::map<std::string, std::string> files_of(std::string_view input) {
  constexpr std::string_view kSeparator = "\n//--\n";
  std::map<std::string, std::string> files;
  for (std::size_t k = 0;; ++k) {
    const std::size_t at = input.find(kSeparator);
    const std::string text(input.substr(0, at));
    files[k == 0 ? std::string(sandpaper::catalog::kIndexDataFile) : sandpaper::catalog::index_part_file(k - 1)] = text;
    if (at == std::string_view::npos) break;
    input.remove_prefix(at + kSeparator.size());
  }
  return files;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  auto files = files_of(std::string_view(reinterpret_cast<const char*>(data), size));
  const auto read = [&](const std::string& path) -> std::optional<std::string> {
    const auto it = files.find(path);
    return it == files.end() ? std::nullopt : std::optional<std::string>(it->second);
  };
  // Two rows as a run that redrew them would give: one that keeps its picture, one that loses it.
  catalog::IndexRow ref;
  ref.name = "ref";
  ref.family = "abrasives";
  ref.describes = "the reference grating </script> \\ '";
  ref.roughness = 0.5;
  ref.max_lateral_force_N = 1.2;
  ref.period_m = 0.0025;
  ref.kind = "grating|grating";
  ref.licence = "CC0-1.0";
  ref.source_kinds = 5;
  ref.page = "entries/ref.html";
  ref.thumbnail = "entries/ref-thumb.png";
  catalog::IndexRow rib;
  rib.name = "rib";
  rib.family = "cloth";
  rib.aliases = {"ribbed-cloth"};
  rib.describes = "ribbed cloth";
  rib.root = "lab";
  rib.page = "entries/rib.html";
  const std::vector<catalog::IndexRow> changed{ref, rib};
  const auto once = catalog::patch_index(read, manifest(), changed);
  if (!once) return 0;
  fuzz::check(once->count(catalog::kIndexDataFile) && once->count("index.html"), "a patch without its head or page");
  for (const auto& [path, text] : *once) files[path] = text;
  const auto twice = catalog::patch_index(read, manifest(), changed);
  fuzz::check(twice.has_value(), "data files this patch wrote are refused by the next patch");
  fuzz::check(*twice == *once, "patching patched data files with the same rows changed them");
  return 0;
}
