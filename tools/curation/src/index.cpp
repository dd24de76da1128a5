// Building the index: compile every entry on one device, then write everything into a temp file
// beside the index and rename it over the old one (atomic on POSIX file systems).
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>

#include <map>
#include <regex>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/curation/display.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/percepts.hpp"
#include "sqlite_util.hpp"

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
CREATE TABLE aliases(alias TEXT PRIMARY KEY, name TEXT NOT NULL REFERENCES entries(name));
CREATE TABLE percepts(name TEXT NOT NULL REFERENCES entries(name), percept TEXT NOT NULL, value REAL NOT NULL);
CREATE TABLE statements(name TEXT NOT NULL REFERENCES entries(name), ordinal INTEGER NOT NULL, line INTEGER NOT NULL,
  keyword TEXT NOT NULL, text TEXT NOT NULL, PRIMARY KEY(name, ordinal));
CREATE TABLE sources(name TEXT NOT NULL REFERENCES entries(name), ordinal INTEGER NOT NULL, kind TEXT NOT NULL,
  text TEXT NOT NULL, line INTEGER NOT NULL);
CREATE TABLE provenance(name TEXT NOT NULL REFERENCES entries(name), ordinal INTEGER NOT NULL, parameter TEXT NOT NULL,
  value_si REAL NOT NULL, si_unit TEXT NOT NULL, stated TEXT NOT NULL, layer TEXT NOT NULL, source TEXT NOT NULL,
  notes TEXT NOT NULL);
CREATE VIRTUAL TABLE search USING fts5(name, aliases, describes, family, sources, tokenize = 'unicode61 remove_diacritics 2');
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

void write_index(const std::filesystem::path& path, const compiler::Library& lib, const std::vector<Compiled>& all,
                 const calibration::CalibrationSet& cal, const std::map<std::string, std::string>& meta,
                 const DisplayPaths& disp) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
    std::string msg = db ? sqlite3_errmsg(db) : "out of memory";
    sqlite3_close(db);
    throw sql::Error("cannot create " + path.string() + ": " + msg);
  }
  struct Closer {
    sqlite3* db;
    ~Closer() { sqlite3_close(db); }
  } closer{db};
  sql::exec(db, "PRAGMA journal_mode = OFF; PRAGMA synchronous = OFF;");  // a temp file: the rename is the commit
  sql::exec(db, "BEGIN");
  sql::exec(db, kSchema);
  {
    sql::Stmt m(db, "INSERT INTO meta VALUES (?, ?)");
    for (const auto& [k, v] : meta) m.bind(1, k).bind(2, v).run();
    sql::Stmt f(db, "INSERT INTO families VALUES (?, ?, ?, ?)");
    int ord = 0;
    for (const auto& fam : lib.manifest().families) f.bind(1, fam.id).bind(2, fam.title).bind(3, fam.describes).bind(4, ord++).run();
  }
  // Entries by the file name the compiler gave them, to find the statement behind each provenance row.
  std::map<std::string, const compiler::LibraryEntry*> by_file;
  for (const auto& e : lib.entries()) {
    by_file["library/" + e.relative_path] = &e;
    by_file[disp.path_of(e.relative_path)] = &e;
  }
  static const std::regex where(R"(([^\s()]+\.hmat):(\d+):(\d+))");

  sql::Stmt ent(db, "INSERT INTO entries VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)");
  sql::Stmt ali(db, "INSERT OR IGNORE INTO aliases VALUES (?, ?)");
  sql::Stmt per(db, "INSERT INTO percepts VALUES (?, ?, ?)");
  sql::Stmt sta(db, "INSERT INTO statements VALUES (?, ?, ?, ?, ?)");
  sql::Stmt src(db, "INSERT INTO sources VALUES (?, ?, ?, ?, ?)");
  sql::Stmt pro(db, "INSERT INTO provenance VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)");
  sql::Stmt fts(db, "INSERT INTO search(name, aliases, describes, family, sources) VALUES (?, ?, ?, ?, ?)");
  for (const auto& c : all) {
    const auto& e = *c.entry;
    const auto pc = percepts_of(c.material, c.program, cal);
    ent.bind(1, e.name).bind(2, e.family).bind(3, e.describes).bind(4, e.licence).bind(5, e.deprecated_by)
        .bind(6, e.relative_path).bind(7, lib.manifest().version).bind(8, join(e.likes, " "))
        .bind(9, pc.roughness).bind(10, pc.max_lateral_force_N).bind(11, pc.texture_kind).bind(12, pc.period_m)
        .bind(13, pc.period_class).bind(14, pc.character).bind(15, pc.terms).bind(16, physical_summary(c.material, c.program))
        .bind(17, nlohmann::json(pc.term_params).dump()).run();
    for (const auto& a : e.aliases)
      if (a != e.name) ali.bind(1, a).bind(2, e.name).run();
    per.bind(1, e.name).bind(2, std::string("roughness")).bind(3, pc.roughness).run();
    for (const auto& [p, v] : pc.others) per.bind(1, e.name).bind(2, p).bind(3, v).run();
    std::vector<std::string> source_texts;
    int ord = 0;
    for (const auto& st : e.syntax.statements) {
      sta.bind(1, e.name).bind(2, ord).bind(3, st.location.line).bind(4, st.keyword).bind(5, st.text).run();
      for (const auto& s : st.sources) {
        src.bind(1, e.name).bind(2, ord).bind(3, std::string(compiler::source_kind_word(s.kind))).bind(4, s.text)
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
      if (auto it = by_file.find(file); it != by_file.end())
        if (const auto* st = statement_at(it->second->syntax, line))
          for (const auto& s : st->sources) notes.push_back({compiler::source_kind_word(s.kind), s.text});
      pro.bind(1, e.name).bind(2, pord++).bind(3, p.parameter).bind(4, p.value_si).bind(5, p.si_unit).bind(6, p.stated)
          .bind(7, p.layer).bind(8, p.source).bind(9, notes.dump()).run();
    }
    const auto* fam = lib.manifest().family(e.family);
    fts.bind(1, e.name).bind(2, join(e.aliases, " ")).bind(3, e.describes)
        .bind(4, e.family + (fam ? " " + fam->title : std::string())).bind(5, join(source_texts, "\n")).run();
  }
  sql::exec(db, "COMMIT");
}

// Removes "<index>.tmp-PID" files left by runs that were killed (kill -9 runs no clean-up), each
// 20 MB or more for a large library; a running build's file is left alone.
void remove_stale_temporaries(const std::filesystem::path& index) {
  std::error_code ec;
  const auto parent = index.parent_path().empty() ? std::filesystem::path(".") : index.parent_path();
  const std::string prefix = index.filename().string() + ".tmp-";
  for (const auto& e : std::filesystem::directory_iterator(parent, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) std::filesystem::remove(e.path(), ec);
  }
}

}  // namespace

IndexBuildResult build_index(const IndexOptions& options, Progress& progress) {
  IndexBuildResult r;
  const auto lib_dir = options.library_dir.empty() ? compiler::default_library_dir() : options.library_dir;
  const auto cal_dir = options.calibration_dir.empty() ? calibration::default_calibration_dir() : options.calibration_dir;
  r.path = options.index_path.empty() ? default_index_path(lib_dir) : options.index_path;
  const compiler::Compiler c(compiler::CompileOptions{options.device, lib_dir, cal_dir});
  const auto& lib = c.library();
  const DisplayPaths disp(lib_dir);
  // Fingerprint first: an edit made while we compile makes the index stale, not wrongly fresh.
  const auto fingerprint = library_fingerprint(lib_dir, cal_dir);

  for (const auto& d : lib.scan_diagnostics().all())
    if (d.severity == compiler::Severity::Error) {
      disp.append_relocated(r.diagnostics, lib.scan_diagnostics());
      break;
    }
  std::vector<Compiled> all;
  for (const auto& e : lib.entries()) {
    if (lib.entry(e.name) != &e) {  // a second file with a taken name: `library check` reports it (E0607)
      progress.step(e.name);
      continue;
    }
    auto res = c.compile_file(disp.path_of(e.relative_path));
    if (!res.ok()) {
      compiler::Diagnostics errors;
      for (const auto& d : res.diagnostics.all())
        if (d.severity == compiler::Severity::Error) errors.error(d.code, d.location, d.message, d.suggestion).notes = d.notes;
      disp.append_relocated(r.diagnostics, errors);
    } else {
      all.push_back({&e, std::move(*res.material), std::move(*res.program)});
    }
    progress.step(e.name);
  }
  r.entries = all.size();
  if (r.diagnostics.has_errors()) return r;

  std::map<std::string, std::string> meta{
      {"schema_version", std::to_string(kIndexSchemaVersion)},
      {"fingerprint", fingerprint},
      {"library_name", lib.manifest().name},
      {"library_version", lib.manifest().version},
      {"library_reference", lib.manifest().reference},
      {"library_dir", std::filesystem::absolute(lib_dir).lexically_normal().string()},
      {"calibration_dir", std::filesystem::absolute(cal_dir).lexically_normal().string()},
      {"device", options.device},
      {"weber_fraction", std::to_string(c.calibration().knowledge().force_jnd.weber_fraction)},
      {"force_jnd_file", c.calibration().knowledge().force_jnd.file},
      {"roughness_map", c.calibration().roughness_map().provenance()},
  };
  std::error_code ec;
  if (r.path.has_parent_path()) std::filesystem::create_directories(r.path.parent_path(), ec);
  remove_stale_temporaries(r.path);
  auto tmp = r.path;
  tmp += ".tmp-" + std::to_string(getpid());
  std::filesystem::remove(tmp, ec);
  try {
    write_index(tmp, lib, all, c.calibration(), meta, disp);
    std::filesystem::rename(tmp, r.path);
  } catch (const std::exception& e) {
    std::filesystem::remove(tmp, ec);
    r.error = e.what();
    return r;
  }
  r.ok = true;
  return r;
}

}  // namespace sandpaper::curation
