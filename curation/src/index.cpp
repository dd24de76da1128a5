// Building the index: into a temp file beside the index, started from a copy of the previous index
// (or the temp file of a build that was killed), compiling only the entries whose inputs changed
// (entry_inputs.hpp), then renamed over the old one (atomic on POSIX file systems).
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <map>
#include <regex>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/display_paths.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/percepts.hpp"
#include "below.hpp"
#include "entry_inputs.hpp"
#include "index_update.hpp"
#include "index_write.hpp"
#include "root_library.hpp"
#include "sqlite_util.hpp"
#include "stamps.hpp"

namespace sandpaper::curation {

namespace {

// Whether `path` is an index of this schema, library folder (over the same roots) and device: then
// its rows can be reused.
bool reusable(const std::filesystem::path& path, const std::string& library_dir, const std::string& device,
              const std::string& below) {
  try {
    const Index idx(path);
    return idx.meta("library_dir") == library_dir && idx.meta("device") == device && idx.meta("below") == below;
  } catch (const std::exception&) {
    return false;
  }
}

std::map<std::string, std::string> input_hashes_in(sqlite3* db) {
  std::map<std::string, std::string> out;
  sql::Stmt s(db, "SELECT name, hash FROM inputs");
  while (s.step()) out[s.text(0)] = s.text(1);
  return out;
}

// "<index>.tmp-PID" files of runs that died (kill -9 runs no clean-up): the newest one that is an
// index of this library is returned, to resume from; the others are removed. A running build's
// file is left alone.
std::filesystem::path stale_temporaries(const std::filesystem::path& index, const std::string& library_dir, const std::string& device,
                                        const std::string& below) {
  std::error_code ec;
  const auto parent = index.parent_path().empty() ? std::filesystem::path(".") : index.parent_path();
  const std::string prefix = index.filename().string() + ".tmp-";
  std::vector<std::filesystem::path> dead;
  for (const auto& e : std::filesystem::directory_iterator(parent, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0 || (name.size() >= 8 && name.compare(name.size() - 8, 8, "-journal") == 0)) continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) dead.push_back(e.path());
  }
  std::sort(dead.begin(), dead.end(), [](const auto& a, const auto& b) {
    std::error_code e1, e2;
    return std::filesystem::last_write_time(a, e1) > std::filesystem::last_write_time(b, e2);
  });
  std::filesystem::path resume;
  for (const auto& d : dead) {
    // Opening it read-write rolls back the transaction the kill interrupted (its hot journal).
    bool ok = false;
    if (resume.empty()) {
      try {
        sqlite3* db = open_rw(d);
        Closer c{db};
        sql::exec(db, "SELECT count(*) FROM inputs");
        ok = true;
      } catch (const std::exception&) {
      }
    }
    if (ok && reusable(d, library_dir, device, below)) {
      resume = d;
      continue;
    }
    std::filesystem::remove(d, ec);
    auto journal = d;
    journal += "-journal";
    std::filesystem::remove(journal, ec);
  }
  return resume;
}

// Whether a build left "<index>.tmp-*" beside the index (running, or killed: then it is resumed).
bool temporaries_beside(const std::filesystem::path& index) {
  std::error_code ec;
  const auto parent = index.parent_path().empty() ? std::filesystem::path(".") : index.parent_path();
  const std::string prefix = index.filename().string() + ".tmp-";
  for (const auto& e : std::filesystem::directory_iterator(parent, ec))
    if (e.path().filename().string().rfind(prefix, 0) == 0) return true;
  return false;
}

// `whole_path`: a layered root compiled over every file of the roots below, not only what its
// entries reach (library_for_root); what a build that failed with the part does again, so that its
// diagnostics (a "did you mean" among every name) are those of the whole path.
IndexBuildResult build(const IndexOptions& options, Progress& progress, bool whole_path) {
  IndexBuildResult r;
  const auto lib_dir = options.library_dir.empty() ? compiler::default_library_dir() : options.library_dir;
  const auto cal_dir = options.calibration_dir.empty() ? calibration::default_calibration_dir() : options.calibration_dir;
  r.path = options.index_path.empty() ? default_index_path(lib_dir) : options.index_path;
  const auto lib_abs = std::filesystem::absolute(lib_dir).lexically_normal().string();
  // Stamps first: an edit made while we compile makes the index stale, not wrongly fresh.
  const auto start = stamps::now_ns();
  if (options.changed) {
    if (options.full || !options.below.empty()) {
      r.error = "a list of changed files is for one library root updated in place, not with a full build or a layered path";
      return r;
    }
    std::string error;
    (void)tag_changed(*options.changed, lib_dir, cal_dir, error);
    if (!error.empty()) {
      r.error = error;
      return r;
    }
  }
  // A few entries changed, and no build was cut off: update the index in place.
  std::error_code exists_ec;
  // (A root of a layered path is small beside the roots under it, and is rebuilt in batches.)
  if (!options.full && options.below.empty() && !temporaries_beside(r.path) && std::filesystem::is_regular_file(r.path, exists_ec)) {
    try {
      if (auto updated = update_in_place(options, lib_dir, cal_dir, r.path, start, progress)) return *updated;
    } catch (const std::exception& e) {
      r.error = e.what();
      return r;
    }
  }
  const bool layered = !options.below.empty();
  std::vector<std::filesystem::path> library_path{lib_dir};
  if (layered) library_path.insert(library_path.end(), options.below.begin(), options.below.end());
  const auto below = below_paths(options.below);
  std::string below_fp;
  if (layered) {
    const auto fp = below_fingerprint(options.below, cal_dir);
    if (!fp) {
      r.error = "the index of a root below " + lib_dir.string() + " is missing or stale: index the roots of the path from the bottom up";
      return r;
    }
    below_fp = *fp;
  }
  const compiler::CompileOptions compile_options{options.device, lib_dir, cal_dir, library_path};
  auto part = layered && !whole_path ? library_for_root(lib_dir, options.below) : std::nullopt;
  r.part_of_path = part.has_value();
  const compiler::Compiler c = part ? compiler::Compiler(compile_options, std::move(*part)) : compiler::Compiler(compile_options);
  const auto& lib = c.library();
  const compiler::DisplayPaths disp(lib);

  for (const auto& d : lib.scan_diagnostics().all())
    if (d.severity == compiler::Severity::Error) {
      disp.append_relocated(r.diagnostics, lib.scan_diagnostics());
      return r;
    }

  std::error_code ec;
  if (r.path.has_parent_path()) std::filesystem::create_directories(r.path.parent_path(), ec);
  auto tmp = r.path;
  tmp += ".tmp-" + std::to_string(getpid());
  auto journal = tmp;
  journal += "-journal";
  auto discard = [&] {
    std::filesystem::remove(tmp, ec);
    std::filesystem::remove(journal, ec);
  };
  try {
    // What to start from: the rows of a build that was killed (resume), else of the previous
    // index, if either is an index of this library for this device; else nothing (a full build).
    std::filesystem::path base = options.full ? std::filesystem::path() : stale_temporaries(r.path, lib_abs, options.device, below);
    discard();
    if (!base.empty()) {
      r.resumed = true;
      std::filesystem::rename(base, tmp);
    } else if (!options.full && reusable(r.path, lib_abs, options.device, below)) {
      std::filesystem::copy_file(r.path, tmp);
    }
    const bool incremental = std::filesystem::exists(tmp);
    sqlite3* db = open_rw(tmp);
    Closer closer{db};
    // Committed in batches with a rollback journal: a kill leaves a consistent file to resume from.
    sql::exec(db, "PRAGMA journal_mode = DELETE; PRAGMA synchronous = OFF;");
    if (!incremental) sql::exec(db, std::string("BEGIN; ") + kIndexSchemaSql + " COMMIT;");

    stamps::Tree tree;
    const auto known = stamps::read_files(db);
    stamps::walk(lib_dir, "library", known, start, false, tree);
    stamps::walk(cal_dir, "calibration", known, start, true, tree);
    r.files_hashed = tree.hashed;
    std::map<std::string, std::string> file_hashes;
    for (const auto& f : tree.files) file_hashes[f.path] = f.hash;
    // Over roots below: what they hold is in their fingerprints, so a change there redoes every entry here.
    const auto global = global_inputs(file_hashes, options.device) + (layered ? "\nbelow\n" + below_fp : std::string());
    const auto inputs = entry_inputs(
        lib,
        [&](const std::string& path) {
          const auto it = file_hashes.find(path);
          return it == file_hashes.end() ? std::string("absent") : it->second;
        },
        global);

    // Rows of entries that are gone or whose inputs changed go first, in one transaction.
    const auto had = input_hashes_in(db);
    {
      sql::exec(db, "BEGIN");
      std::vector<std::string> stale;
      sql::Stmt names(db, "SELECT name FROM entries");
      while (names.step()) {
        const auto name = names.text(0);
        const auto now = inputs.find(name);
        const auto then = had.find(name);
        if (now == inputs.end() || then == had.end() || then->second != now->second.hash) stale.push_back(name);
      }
      for (const auto& n : stale) delete_entry(db, n);
      sql::exec(db, "COMMIT");
    }

    progress.set_total(static_cast<std::size_t>(
        std::count_if(lib.entries().begin(), lib.entries().end(), [](const auto& e) { return e.root == 0; })));
    EntryWriter writer(db, lib, c.calibration(), disp);
    std::size_t in_batch = 0;
    sql::exec(db, "BEGIN");
    for (const auto& e : lib.entries()) {
      if (e.root != 0) continue;  // indexed with its own root
      if (lib.entry(e.name) != &e) {  // a second file with a taken name: `library check` reports it (E0607)
        progress.step(e.name);
        continue;
      }
      const auto& in = inputs.at(e.name);
      if (auto then = had.find(e.name); then != had.end() && then->second == in.hash) {
        ++r.reused;
        ++r.entries;
        progress.step(e.name);
        continue;
      }
      auto res = c.compile_file(disp.path_of(e));
      if (!res.ok()) {
        compiler::Diagnostics errors;
        for (const auto& d : res.diagnostics.all())
          if (d.severity == compiler::Severity::Error) errors.error(schema::Code::of(d.code), d.location, d.message, d.suggestion).notes = d.notes;
        disp.append_relocated(r.diagnostics, errors);
      } else if (!r.diagnostics.has_errors()) {
        writer.insert({&e, std::move(*res.material), std::move(*res.program)}, in);
        ++r.compiled;
        ++r.entries;
        if (++in_batch >= std::max<std::size_t>(options.batch, 1)) {
          sql::exec(db, "COMMIT; BEGIN");
          in_batch = 0;
        }
      }
      progress.step(e.name);
    }
    sql::exec(db, "COMMIT");
    if (r.diagnostics.has_errors()) {
      sqlite3_close(db);
      closer.db = nullptr;
      discard();
      return r;
    }
    auto meta = index_meta(c, lib_abs, cal_dir, options.device, stamps::fingerprint(tree.files), stamps::fnv_hex(global));
    meta["below"] = below;
    meta["below_fingerprint"] = below_fp;
    sql::exec(db, "BEGIN");
    write_families_and_meta(db, lib, meta);
    stamps::write(db, tree);
    sql::exec(db, "COMMIT");
    sqlite3_close(db);
    closer.db = nullptr;
    std::filesystem::rename(tmp, r.path);
  } catch (const std::exception& e) {
    discard();
    r.error = e.what();
    return r;
  }
  r.ok = true;
  return r;
}

}  // namespace

IndexBuildResult build_index(const IndexOptions& options, Progress& progress) {
  auto r = build(options, progress, false);
  if (!r.ok && r.error.empty() && r.part_of_path) r = build(options, progress, true);
  return r;
}

}  // namespace sandpaper::curation
