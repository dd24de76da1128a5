#pragma once
// The catalog's record of what it drew (internal to sandpaper_catalog): inputs.sqlite in the
// catalog folder, one row an entry (its input hash, its index row, its files under entries/) and
// the picture settings. SQLite rather than one JSON file: at 100,000 entries the JSON was 59 MB
// to read and write whole, where an update of a few entries changes a few rows in a transaction.
#include <filesystem>
#include <unordered_map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sandpaper/catalog/index_page.hpp"

struct sqlite3;

namespace sandpaper::catalog {

inline constexpr const char* kRecordFile = "inputs.sqlite";

// A name this program writes under entries/: not empty, no folder separator, no NUL, no leading dot
// (so neither "." nor ".." nor a hidden file).
bool plain_file_name(std::string_view name);

struct RecordedEntry {
  std::string hash;        // the entry's input hash when drawn (docs/LIBRARY.md, "Incremental builds")
  IndexRow row;
  std::string files_json;  // its files under entries/, a JSON array: parsed only for the entries a run touches
  // Those files, if the record names them as this program writes them: plain file names (no folder,
  // no "..", no leading dot). nullopt otherwise (bad JSON, or a name reaching outside entries/): a
  // record from elsewhere must not make a run delete, link or publish a file outside the catalog.
  std::optional<std::vector<std::string>> files() const;
};
using Record = std::unordered_map<std::string, RecordedEntry>;

// The record in `dir`, if there is one drawn with `settings` and every row asked for reads whole
// (else nullopt: draw everything). `only`: just these entries (those absent are left out); nullptr: every entry.
std::optional<Record> read_record(const std::filesystem::path& dir, const std::string& settings,
                                  const std::vector<std::string>* only = nullptr);
// Just each entry's input hash: what a run compares to decide what to draw. `only` as for read_record.
std::optional<std::unordered_map<std::string, std::string>> read_record_hashes(const std::filesystem::path& dir,
                                                                               const std::string& settings,
                                                                               const std::vector<std::string>* only = nullptr);
// The fingerprint of the library index whose input hashes the record's rows were compared with when
// it was last committed ("" if none: drawn without an index, or by an earlier version).
std::string recorded_index_fingerprint(const std::filesystem::path& dir, const std::string& settings);

// Writes a record: a new file, or the catalog's own in place. Rows go in one transaction, which
// commit() ends; destroyed before commit(), nothing it wrote is kept.
class RecordWriter {
 public:
  RecordWriter(const std::filesystem::path& file, const std::string& settings);
  ~RecordWriter();
  RecordWriter(const RecordWriter&) = delete;
  RecordWriter& operator=(const RecordWriter&) = delete;
  void put(const std::string& name, const RecordedEntry& e);
  void erase(const std::string& name);
  void set_index_fingerprint(const std::string& fingerprint);  // see recorded_index_fingerprint
  void commit();

 private:
  sqlite3* db_ = nullptr;
  bool open_ = false;
};

}  // namespace sandpaper::catalog
