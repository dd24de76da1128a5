// The catalog's record (inputs.sqlite in the catalog folder, curation/catalog/src/record.hpp), read by
// every run to decide what to draw and, in place, which old files to delete. Any bytes there give a
// record or none, never a crash; and no file list it yields names anything outside entries/
// (a record from elsewhere must not make a run delete or publish files outside the catalog).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "record.hpp"

namespace {

// The picture settings the corpus's records were written with (catalog.cpp settings_of, defaults).
const std::string kSettings = R"({"arrays":false,"format":3,"picture_side":384,"thumbnail_side":128,"thumbnail_window_m":0.04})";

void check_files(const sandpaper::catalog::RecordedEntry& e) {
  const auto files = e.files();
  if (!files) return;
  for (const auto& f : *files)
    sandpaper::fuzz::check(!f.empty() && f[0] != '.' && f.find_first_of(std::string_view("/\\\0", 3)) == std::string::npos,
                           "a recorded file name reaches outside entries/: " + f);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const auto dir = fuzz::scratch_dir() / "catalog";
  std::filesystem::create_directories(dir);
  for (const char* side : {"inputs.sqlite-journal", "inputs.sqlite-wal", "inputs.sqlite-shm"}) std::filesystem::remove(dir / side);
  fuzz::write_file(dir / catalog::kRecordFile, std::string_view(reinterpret_cast<const char*>(data), size));
  const auto hashes = catalog::read_record_hashes(dir, kSettings);
  const auto all = catalog::read_record(dir, kSettings);
  if (all) {
    // Every row read whole, so the hashes (fewer columns of the same rows) read too, and name the same entries.
    fuzz::check(hashes && hashes->size() == all->size(), "the record's rows read and its hashes do not, or name other entries");
    for (const auto& [name, e] : *all) {
      // What a run compares (the hashes) and what it then reads (the rows) are the same entries.
      fuzz::check(!hashes || hashes->count(name) == 1, "an entry the record's rows have and its hashes lack: " + name);
      check_files(e);
    }
    std::vector<std::string> some{"ref", "rib", "no-such-entry"};
    if (const auto part = catalog::read_record(dir, kSettings, &some)) {
      for (const auto& [name, e] : *part) check_files(e);
      // The hashes of some entries (a run after an in-place index update) are of the same entries.
      if (const auto part_hashes = catalog::read_record_hashes(dir, kSettings, &some))
        for (const auto& [name, hash] : *part_hashes)
          fuzz::check(part->count(name) == 1, "a listed entry with a hash and no row: " + name);
    }
  }
  (void)catalog::recorded_index_fingerprint(dir, kSettings);
  return 0;
}
