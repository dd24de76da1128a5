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
#include "sandpaper/curation/display.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/percepts.hpp"
#include "entry_inputs.hpp"
#include "sqlite_util.hpp"
#include "stamps.hpp"

namespace sandpaper::curation {

namespace {

const char* kSchema = R"sql(
CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE families(id TEXT PRIMARY KEY, title TEXT NOT NULL, describes TEXT NOT NULL, ord INTEGER NOT NULL);
CREATE TABLE entries(
  name TEXT PRIMARY KEY, family TEXT NOT NULL, describes TEXT NOT NULL, licence TEXT NOT NULL,
  deprecated_by TEXT NOT NULL, file TEXT NOT NULL, library_version TEXT NOT NULL, likes TEXT NOT NULL,
  roughness REAL NOT NULL, max_lateral_force_N REAL NOT NULL, texture_kind TEXT NOT NULL, period_m REAL NOT NULL,
  period_class TEXT NOT NULL, character TEXT NOT NULL, terms TEXT NOT NULL, physical TEXT NOT NULL,
  term_params TEXT NOT NULL);
CREATE INDEX entries_force ON entries(max_lateral_force_N);
CREATE TABLE aliases(alias TEXT PRIMARY KEY, name TEXT NOT NULL REFERENCES entries(name));
CREATE INDEX aliases_name ON aliases(name);
CREATE TABLE percepts(name TEXT NOT NULL REFERENCES entries(name), percept TEXT NOT NULL, value REAL NOT NULL);
CREATE INDEX percepts_name ON percepts(name);
CREATE TABLE statements(name TEXT NOT NULL REFERENCES entries(name), ordinal INTEGER NOT NULL, line INTEGER NOT NULL,
  keyword TEXT NOT NULL, text TEXT NOT NULL, PRIMARY KEY(name, ordinal));
CREATE TABLE sources(name TEXT NOT NULL REFERENCES entries(name), ordinal INTEGER NOT NULL, kind TEXT NOT NULL,
  text TEXT NOT NULL, line INTEGER NOT NULL);
CREATE INDEX sources_name ON sources(name, ordinal);
CREATE TABLE provenance(name TEXT NOT NULL REFERENCES entries(name), ordinal INTEGER NOT NULL, parameter TEXT NOT NULL,
  value_si REAL NOT NULL, si_unit TEXT NOT NULL, stated TEXT NOT NULL, layer TEXT NOT NULL, source TEXT NOT NULL,
  notes TEXT NOT NULL);
CREATE INDEX provenance_name ON provenance(name, ordinal);
CREATE TABLE inputs(name TEXT PRIMARY KEY REFERENCES entries(name), hash TEXT NOT NULL);
CREATE VIRTUAL TABLE search USING fts5(name, aliases, describes, family, sources, tokenize = 'unicode61 remove_diacritics 2');
CREATE TABLE classes(id INTEGER PRIMARY KEY, kind_terms TEXT NOT NULL UNIQUE);
CREATE VIRTUAL TABLE coordinates USING rtree(id, log_force_min, log_force_max, log_period_min, log_period_max, class_min, class_max);
)sql";

struct Compiled {
  const compiler::LibraryEntry* entry;
  compiler::ResolvedMaterial material;
  schema::PatchProgram program;
};

// The statement of `syntax` that a provenance location (line) points into: the last one starting at or before it.
const compiler::Statement* statement_at(const compiler::MaterialSyntax& syntax, int line) {
  const compiler::Statement* found = nullptr;
  for (const auto& st : syntax.statements)
    if (st.location.line <= line) found = &st;
  return found;
}

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

sqlite3* open_rw(const std::filesystem::path& path) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
    std::string msg = db ? sqlite3_errmsg(db) : "out of memory";
    sqlite3_close(db);
    throw sql::Error("cannot open " + path.string() + ": " + msg);
  }
  return db;
}

struct Closer {
  sqlite3* db;
  ~Closer() { sqlite3_close(db); }
};

// Writes one compiled entry's rows, and its input hash with them (one transaction holds both, so
// an interrupted build that is resumed reuses exactly the entries whose rows are complete).
class EntryWriter {
 public:
  EntryWriter(sqlite3* db, const compiler::Library& lib, const calibration::CalibrationSet& cal, const DisplayPaths& disp)
      : db_(db), lib_(lib), cal_(cal),
        ent_(db, "INSERT INTO entries VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)"),
        ali_(db, "INSERT OR IGNORE INTO aliases VALUES (?, ?)"),
        per_(db, "INSERT INTO percepts VALUES (?, ?, ?)"),
        sta_(db, "INSERT INTO statements VALUES (?, ?, ?, ?, ?)"),
        src_(db, "INSERT INTO sources VALUES (?, ?, ?, ?, ?)"),
        pro_(db, "INSERT INTO provenance VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)"),
        fts_(db, "INSERT INTO search(rowid, name, aliases, describes, family, sources) VALUES (?, ?, ?, ?, ?, ?)"),
        geo_(db, "INSERT INTO coordinates VALUES (?, ?, ?, ?, ?, ?, ?)"),
        cls_(db, "INSERT OR IGNORE INTO classes(kind_terms) VALUES (?)"),
        cls_id_(db, "SELECT id FROM classes WHERE kind_terms = ?"),
        inp_(db, "INSERT INTO inputs VALUES (?, ?)") {
    // Entries by the file name the compiler gave them, to find the statement behind each provenance row.
    for (const auto& e : lib.entries()) {
      by_file_["library/" + e.relative_path] = &e;
      by_file_[disp.path_of(e.relative_path)] = &e;
    }
  }

  void insert(const Compiled& c, const std::string& input_hash) {
    static const std::regex where(R"(([^\s()]+\.hmat):(\d+):(\d+))");
    const auto& e = *c.entry;
    const auto pc = percepts_of(c.material, c.program, cal_);
    ent_.bind(1, e.name).bind(2, e.family).bind(3, e.describes).bind(4, e.licence).bind(5, e.deprecated_by)
        .bind(6, e.relative_path).bind(7, lib_.manifest().version).bind(8, join(e.likes, " "))
        .bind(9, pc.roughness).bind(10, pc.max_lateral_force_N).bind(11, pc.texture_kind).bind(12, pc.period_m)
        .bind(13, pc.period_class).bind(14, pc.character).bind(15, pc.terms).bind(16, physical_summary(c.material, c.program))
        .bind(17, nlohmann::json(pc.term_params).dump()).run();
    const auto rowid = static_cast<std::int64_t>(sqlite3_last_insert_rowid(db_));
    for (const auto& a : e.aliases)
      if (a != e.name) ali_.bind(1, a).bind(2, e.name).run();
    per_.bind(1, e.name).bind(2, std::string("roughness")).bind(3, pc.roughness).run();
    for (const auto& [p, v] : pc.others) per_.bind(1, e.name).bind(2, p).bind(3, v).run();
    std::vector<std::string> source_texts;
    int ord = 0;
    for (const auto& st : e.syntax.statements) {
      sta_.bind(1, e.name).bind(2, ord).bind(3, st.location.line).bind(4, st.keyword).bind(5, st.text).run();
      for (const auto& s : st.sources) {
        src_.bind(1, e.name).bind(2, ord).bind(3, std::string(compiler::source_kind_word(s.kind))).bind(4, s.text)
            .bind(5, s.location.line).run();
        source_texts.push_back(s.text);
      }
      ++ord;
    }
    int pord = 0;
    for (const auto& p : c.program.provenance) {
      nlohmann::json notes = nlohmann::json::array();
      std::string rest = p.source, file;
      int line = 0;
      for (std::smatch mm; std::regex_search(rest, mm, where); rest = mm.suffix()) file = mm[1], line = std::stoi(mm[2]);
      if (auto it = by_file_.find(file); it != by_file_.end())
        if (const auto* st = statement_at(it->second->syntax, line))
          for (const auto& s : st->sources) notes.push_back({compiler::source_kind_word(s.kind), s.text});
      pro_.bind(1, e.name).bind(2, pord++).bind(3, p.parameter).bind(4, p.value_si).bind(5, p.si_unit).bind(6, p.stated)
          .bind(7, p.layer).bind(8, p.source).bind(9, notes.dump()).run();
    }
    const auto* fam = lib_.manifest().family(e.family);
    fts_.bind64(1, rowid).bind(2, e.name).bind(3, join(e.aliases, " ")).bind(4, e.describes)
        .bind(5, e.family + (fam ? " " + fam->title : std::string())).bind(6, join(source_texts, "\n")).run();
    // `near` looks up textured entries by (ln force, log2 period) in an R*Tree; no period: the
    // whole period axis, so a box query over force alone finds it (near.cpp).
    if (pc.max_lateral_force_N > 0) {
      const double f = std::log(pc.max_lateral_force_N);
      const double lo = pc.period_m > 0 ? std::log2(pc.period_m) : -1e30, hi = pc.period_m > 0 ? std::log2(pc.period_m) : 1e30;
      // Entries of another texture kind or other terms are kKindSteps or more apart: a third axis.
      const std::string kind_terms = pc.texture_kind + "|" + pc.terms;
      cls_.bind(1, kind_terms).run();
      cls_id_.bind(1, kind_terms);
      cls_id_.step();
      const double cls = static_cast<double>(cls_id_.integer64(0));
      cls_id_.reset();
      geo_.bind64(1, rowid).bind(2, f).bind(3, f).bind(4, lo).bind(5, hi).bind(6, cls).bind(7, cls).run();
    }
    inp_.bind(1, e.name).bind(2, input_hash).run();
  }

 private:
  sqlite3* db_;
  const compiler::Library& lib_;
  const calibration::CalibrationSet& cal_;
  sql::Stmt ent_, ali_, per_, sta_, src_, pro_, fts_, geo_, cls_, cls_id_, inp_;
  std::map<std::string, const compiler::LibraryEntry*> by_file_;
};

void delete_entry(sqlite3* db, const std::string& name) {
  sql::Stmt id(db, "SELECT rowid FROM entries WHERE name = ?");
  id.bind(1, name);
  if (id.step()) {
    const auto rowid = id.integer64(0);
    sql::Stmt(db, "DELETE FROM search WHERE rowid = ?").bind64(1, rowid).run();
    sql::Stmt(db, "DELETE FROM coordinates WHERE id = ?").bind64(1, rowid).run();
  }
  for (const char* table : {"aliases", "percepts", "statements", "sources", "provenance", "inputs", "entries"})
    sql::Stmt(db, std::string("DELETE FROM ") + table + " WHERE name = ?").bind(1, name).run();
}

void write_families_and_meta(sqlite3* db, const compiler::Library& lib, const std::map<std::string, std::string>& meta) {
  sql::exec(db, "DELETE FROM meta; DELETE FROM families;");
  sql::Stmt m(db, "INSERT INTO meta VALUES (?, ?)");
  for (const auto& [k, v] : meta) m.bind(1, k).bind(2, v).run();
  sql::Stmt f(db, "INSERT INTO families VALUES (?, ?, ?, ?)");
  int ord = 0;
  for (const auto& fam : lib.manifest().families) f.bind(1, fam.id).bind(2, fam.title).bind(3, fam.describes).bind(4, ord++).run();
}

// Whether `path` is an index of this schema, library folder and device: then its rows can be reused.
bool reusable(const std::filesystem::path& path, const std::string& library_dir, const std::string& device) {
  try {
    const Index idx(path);
    return idx.meta("library_dir") == library_dir && idx.meta("device") == device;
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
std::filesystem::path stale_temporaries(const std::filesystem::path& index, const std::string& library_dir, const std::string& device) {
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
    if (ok && reusable(d, library_dir, device)) {
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

}  // namespace

IndexBuildResult build_index(const IndexOptions& options, Progress& progress) {
  IndexBuildResult r;
  const auto lib_dir = options.library_dir.empty() ? compiler::default_library_dir() : options.library_dir;
  const auto cal_dir = options.calibration_dir.empty() ? calibration::default_calibration_dir() : options.calibration_dir;
  r.path = options.index_path.empty() ? default_index_path(lib_dir) : options.index_path;
  const auto lib_abs = std::filesystem::absolute(lib_dir).lexically_normal().string();
  // Stamps first: an edit made while we compile makes the index stale, not wrongly fresh.
  const auto start = stamps::now_ns();
  const compiler::Compiler c(compiler::CompileOptions{options.device, lib_dir, cal_dir, {}});
  const auto& lib = c.library();
  const DisplayPaths disp(lib_dir);

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
    std::filesystem::path base = options.full ? std::filesystem::path() : stale_temporaries(r.path, lib_abs, options.device);
    discard();
    if (!base.empty()) {
      r.resumed = true;
      std::filesystem::rename(base, tmp);
    } else if (!options.full && reusable(r.path, lib_abs, options.device)) {
      std::filesystem::copy_file(r.path, tmp);
    }
    const bool incremental = std::filesystem::exists(tmp);
    sqlite3* db = open_rw(tmp);
    Closer closer{db};
    // Committed in batches with a rollback journal: a kill leaves a consistent file to resume from.
    sql::exec(db, "PRAGMA journal_mode = DELETE; PRAGMA synchronous = OFF;");
    if (!incremental) sql::exec(db, std::string("BEGIN; ") + kSchema + " COMMIT;");

    stamps::Tree tree;
    const auto known = stamps::read_files(db);
    stamps::walk(lib_dir, "library", known, start, false, tree);
    stamps::walk(cal_dir, "calibration", known, start, true, tree);
    r.files_hashed = tree.hashed;
    std::map<std::string, std::string> file_hashes;
    std::string all_files = "sandpaper-library-index/" + std::to_string(kIndexSchemaVersion);
    for (const auto& f : tree.files) {
      file_hashes[f.path] = f.hash;
      all_files += "\n" + f.path + " " + f.hash;
    }
    const auto inputs = entry_input_hashes(lib, file_hashes, global_inputs(file_hashes, options.device));

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
        if (now == inputs.end() || then == had.end() || then->second != now->second) stale.push_back(name);
      }
      for (const auto& n : stale) delete_entry(db, n);
      sql::exec(db, "COMMIT");
    }

    EntryWriter writer(db, lib, c.calibration(), disp);
    std::size_t in_batch = 0;
    sql::exec(db, "BEGIN");
    for (const auto& e : lib.entries()) {
      if (lib.entry(e.name) != &e) {  // a second file with a taken name: `library check` reports it (E0607)
        progress.step(e.name);
        continue;
      }
      const auto& hash = inputs.at(e.name);
      if (auto then = had.find(e.name); then != had.end() && then->second == hash) {
        ++r.reused;
        ++r.entries;
        progress.step(e.name);
        continue;
      }
      auto res = c.compile_file(disp.path_of(e.relative_path));
      if (!res.ok()) {
        compiler::Diagnostics errors;
        for (const auto& d : res.diagnostics.all())
          if (d.severity == compiler::Severity::Error) errors.error(d.code, d.location, d.message, d.suggestion).notes = d.notes;
        disp.append_relocated(r.diagnostics, errors);
      } else if (!r.diagnostics.has_errors()) {
        writer.insert({&e, std::move(*res.material), std::move(*res.program)}, hash);
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
    const std::map<std::string, std::string> meta{
        {"schema_version", std::to_string(kIndexSchemaVersion)},
        {"fingerprint", stamps::fnv_hex(all_files)},
        {"library_name", lib.manifest().name},
        {"library_version", lib.manifest().version},
        {"library_reference", lib.manifest().reference},
        {"library_dir", lib_abs},
        {"calibration_dir", std::filesystem::absolute(cal_dir).lexically_normal().string()},
        {"device", options.device},
        {"weber_fraction", std::to_string(c.calibration().knowledge().force_jnd.weber_fraction)},
        {"force_jnd_file", c.calibration().knowledge().force_jnd.file},
        {"roughness_map", c.calibration().roughness_map().provenance()},
    };
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

}  // namespace sandpaper::curation
