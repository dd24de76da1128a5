#pragma once
// Writing the index's rows (internal to sandpaper_curation): the schema, one entry's rows, the
// families and meta rows. Used by the batched build (index.cpp) and the in-place update
// (index_update.cpp).
#include <filesystem>
#include <map>
#include <string>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/display_paths.hpp"
#include "entry_inputs.hpp"
#include "sqlite_util.hpp"

namespace sandpaper::curation {

extern const char* const kIndexSchemaSql;

sqlite3* open_rw(const std::filesystem::path& path);

struct Closer {
  sqlite3* db;
  ~Closer() { sqlite3_close(db); }
};

struct Compiled {
  const compiler::LibraryEntry* entry;
  compiler::ResolvedMaterial material;
  schema::PatchProgram program;
};

// Writes one compiled entry's rows, with its input hash and what it was built from (one
// transaction holds them all, so an interrupted build that is resumed reuses exactly the entries
// whose rows are complete).
class EntryWriter {
 public:
  EntryWriter(sqlite3* db, const compiler::Library& lib, const calibration::CalibrationSet& cal, const compiler::DisplayPaths& disp);
  void insert(const Compiled& c, const EntryInputs& inputs);

 private:
  sqlite3* db_;
  const compiler::Library& lib_;
  const calibration::CalibrationSet& cal_;
  sql::Stmt ent_, ali_, per_, sta_, src_, pro_, fts_, geo_, law_, cls_, cls_id_, inp_, dep_;
  std::map<std::string, const compiler::LibraryEntry*> by_file_;
};

// Removes every row of entry `name`.
void delete_entry(sqlite3* db, const std::string& name);

// The meta rows of an index built from `lib` by `c` (fingerprint: of the file list; global: of
// global_inputs()).
std::map<std::string, std::string> index_meta(const compiler::Compiler& c, const std::string& library_dir_abs,
                                              const std::filesystem::path& calibration_dir, const std::string& device,
                                              const std::string& fingerprint, const std::string& global);
void write_families_and_meta(sqlite3* db, const compiler::Library& lib, const std::map<std::string, std::string>& meta);

}  // namespace sandpaper::curation
