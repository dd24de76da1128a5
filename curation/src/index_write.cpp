// Writing the index's rows: see index_write.hpp.
#include "index_write.hpp"

#include <cmath>
#include <regex>

#include <nlohmann/json.hpp>

#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/percepts.hpp"

namespace sandpaper::curation {

const char* const kIndexSchemaSql = R"sql(
CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE families(id TEXT PRIMARY KEY, title TEXT NOT NULL, describes TEXT NOT NULL, ord INTEGER NOT NULL, stimulus_set INTEGER NOT NULL);
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
CREATE INDEX entries_file ON entries(file);
CREATE TABLE inputs(name TEXT PRIMARY KEY REFERENCES entries(name), hash TEXT NOT NULL);
CREATE TABLE depends(name TEXT NOT NULL REFERENCES entries(name), kind TEXT NOT NULL, target TEXT NOT NULL);
CREATE INDEX depends_target ON depends(target, kind);
CREATE INDEX depends_name ON depends(name);
CREATE VIRTUAL TABLE search USING fts5(name, aliases, describes, family, tokenize = 'porter unicode61 remove_diacritics 2');
CREATE TABLE classes(id INTEGER PRIMARY KEY, kind_terms TEXT NOT NULL UNIQUE);
CREATE VIRTUAL TABLE coordinates USING rtree(id, log_force_min, log_force_max, log_period_min, log_period_max, class_min, class_max);
CREATE VIRTUAL TABLE laws USING rtree(id, stiffness_min, stiffness_max, damping_min, damping_max, friction_min, friction_max, class_min, class_max);
)sql";

namespace {

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

}  // namespace



sqlite3* open_rw(const std::filesystem::path& path) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
    std::string msg = db ? sqlite3_errmsg(db) : "out of memory";
    sqlite3_close(db);
    throw sql::Error("cannot open " + path.string() + ": " + msg);
  }
  return db;
}


EntryWriter::EntryWriter(sqlite3* db, const compiler::Library& lib, const calibration::CalibrationSet& cal, const compiler::DisplayPaths& disp)
      : db_(db), lib_(lib), cal_(cal),
        ent_(db, "INSERT INTO entries VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)"),
        ali_(db, "INSERT OR IGNORE INTO aliases VALUES (?, ?)"),
        per_(db, "INSERT INTO percepts VALUES (?, ?, ?)"),
        sta_(db, "INSERT INTO statements VALUES (?, ?, ?, ?, ?)"),
        src_(db, "INSERT INTO sources VALUES (?, ?, ?, ?, ?)"),
        pro_(db, "INSERT INTO provenance VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)"),
        fts_(db, "INSERT INTO search(rowid, name, aliases, describes, family) VALUES (?, ?, ?, ?, ?)"),
        geo_(db, "INSERT INTO coordinates VALUES (?, ?, ?, ?, ?, ?, ?)"),
        law_(db, "INSERT INTO laws VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)"),
        cls_(db, "INSERT OR IGNORE INTO classes(kind_terms) VALUES (?)"),
        cls_id_(db, "SELECT id FROM classes WHERE kind_terms = ?"),
        inp_(db, "INSERT INTO inputs VALUES (?, ?)"),
        dep_(db, "INSERT INTO depends VALUES (?, ?, ?)") {
    // Entries by the file name the compiler gave them, to find the statement behind each provenance row.
    for (const auto& e : lib.entries()) {
      by_file_[lib.source_name(e)] = &e;
      by_file_[disp.path_of(e)] = &e;
    }
}

void EntryWriter::insert(const Compiled& c, const EntryInputs& inputs) {
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
    int ord = 0;
    for (const auto& st : e.syntax.statements) {
      sta_.bind(1, e.name).bind(2, ord).bind(3, st.location.line).bind(4, st.keyword).bind(5, st.text).run();
      for (const auto& s : st.sources) {
        src_.bind(1, e.name).bind(2, ord).bind(3, std::string(compiler::source_kind_word(s.kind))).bind(4, s.text)
            .bind(5, s.location.line).run();
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
        .bind(5, e.family + (fam ? " " + fam->title + " " + fam->describes : std::string())).run();
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
    } else {
      // An untextured entry by its force laws: stiffness, damping and friction coefficient in their
      // percepts' JNDs (a dimension it lacks spans the axis), and its terms as the class.
      const auto place = law_coordinates(pc.term_params, weber_fractions_of(cal_));
      const std::string kind_terms = "|" + pc.terms;
      cls_.bind(1, kind_terms).run();
      cls_id_.bind(1, kind_terms);
      cls_id_.step();
      const double cls = static_cast<double>(cls_id_.integer64(0));
      cls_id_.reset();
      law_.bind64(1, rowid);
      for (std::size_t d = 0; d < place.size(); ++d)
        law_.bind(static_cast<int>(2 + 2 * d), place[d] ? *place[d] : -1e30).bind(static_cast<int>(3 + 2 * d), place[d] ? *place[d] : 1e30);
      law_.bind(8, cls).bind(9, cls).run();
    }
    inp_.bind(1, e.name).bind(2, inputs.hash).run();
    for (const auto& f : inputs.files) dep_.bind(1, e.name).bind(2, std::string("file")).bind(3, f).run();
    for (const auto& n : inputs.entries) dep_.bind(1, e.name).bind(2, std::string("entry")).bind(3, n).run();
}

void delete_entry(sqlite3* db, const std::string& name) {
  sql::Stmt id(db, "SELECT rowid FROM entries WHERE name = ?");
  id.bind(1, name);
  if (id.step()) {
    const auto rowid = id.integer64(0);
    sql::Stmt(db, "DELETE FROM search WHERE rowid = ?").bind64(1, rowid).run();
    sql::Stmt(db, "DELETE FROM coordinates WHERE id = ?").bind64(1, rowid).run();
    sql::Stmt(db, "DELETE FROM laws WHERE id = ?").bind64(1, rowid).run();
  }
  for (const char* table : {"aliases", "percepts", "statements", "sources", "provenance", "inputs", "depends", "entries"})
    sql::Stmt(db, std::string("DELETE FROM ") + table + " WHERE name = ?").bind(1, name).run();
}

void write_families_and_meta(sqlite3* db, const compiler::Library& lib, const std::map<std::string, std::string>& meta) {
  sql::exec(db, "DELETE FROM meta; DELETE FROM families;");
  sql::Stmt m(db, "INSERT INTO meta VALUES (?, ?)");
  for (const auto& [k, v] : meta) m.bind(1, k).bind(2, v).run();
  sql::Stmt f(db, "INSERT INTO families VALUES (?, ?, ?, ?, ?)");
  int ord = 0;
  for (const auto& fam : lib.manifest().families) f.bind(1, fam.id).bind(2, fam.title).bind(3, fam.describes).bind(4, ord++).bind(5, fam.stimulus_set ? 1 : 0).run();
}

std::map<std::string, std::string> index_meta(const compiler::Compiler& c, const std::string& library_dir_abs,
                                              const std::filesystem::path& calibration_dir, const std::string& device,
                                              const std::string& fingerprint, const std::string& global) {
  const auto& lib = c.library();
  return {
      {"schema_version", std::to_string(kIndexSchemaVersion)},
      {"fingerprint", fingerprint},
      {"global_inputs", global},
      {"library_name", lib.manifest().name},
      {"library_id", lib.roots().front().id},
      {"library_version", lib.manifest().version},
      {"library_reference", lib.manifest().reference},
      {"library_dir", library_dir_abs},
      {"calibration_dir", std::filesystem::absolute(calibration_dir).lexically_normal().string()},
      {"device", device},
      {"weber_fraction", std::to_string(c.calibration().knowledge().force_jnd.weber_fraction)},
      {"weber_fraction.stiffness", std::to_string(weber_fractions_of(c.calibration()).stiffness)},
      {"weber_fraction.damping", std::to_string(weber_fractions_of(c.calibration()).damping)},
      {"weber_fraction.friction", std::to_string(weber_fractions_of(c.calibration()).friction)},
      {"force_jnd_file", c.calibration().knowledge().force_jnd.file},
      {"roughness_map", c.calibration().roughness_map().provenance()},
  };
}

}  // namespace sandpaper::curation
