#include <nlohmann/json.hpp>

#include <cstdlib>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "sandpaper/curation/index.hpp"
#include "below.hpp"
#include "sqlite_util.hpp"
#include "reach.hpp"
#include "stamps.hpp"

namespace sandpaper::curation {

Index::Index(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw IndexError("no index at " + path.string());
  // A journal beside the index: an update was killed before its commit. Opening it read-write
  // rolls that back (the old index); a reader without write access gets SQLite's error below.
  auto journal = path;
  journal += "-journal";
  if (std::filesystem::exists(journal, ec)) {
    sqlite3* rw = nullptr;
    if (sqlite3_open_v2(path.c_str(), &rw, SQLITE_OPEN_READWRITE, nullptr) == SQLITE_OK)
      sqlite3_exec(rw, "SELECT count(*) FROM sqlite_master", nullptr, nullptr, nullptr);
    sqlite3_close(rw);
  }
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw IndexError("cannot open the index " + path.string() + ": " + msg);
  }
  sqlite3_busy_timeout(db_, 10'000);  // an update commits in place (index_update.cpp)
  std::string version;
  try {
    version = meta("schema_version");
  } catch (const std::exception& e) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw IndexError(path.string() + " is not a library index (" + e.what() + ")");
  }
  if (version != std::to_string(kIndexSchemaVersion)) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw IndexError(path.string() + " is an index of schema " + (version.empty() ? "?" : version) + ", not " +
                     std::to_string(kIndexSchemaVersion) + ": rebuild it with `sandpaper library index`");
  }
}

Index::Index(sqlite3* db) : db_(db) {
  const auto version = meta("schema_version");
  if (version != std::to_string(kIndexSchemaVersion)) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw IndexError("an index of schema " + (version.empty() ? std::string("?") : version) + ", not " + std::to_string(kIndexSchemaVersion));
  }
}

Index::~Index() { sqlite3_close(db_); }

std::string Index::meta(const std::string& key) const {
  sql::Stmt s(db_, "SELECT value FROM meta WHERE key = ?");
  s.bind(1, key);
  return s.step() ? s.text(0) : std::string();
}

// The error for an index whose contents were edited or damaged since it was written (F43): names
// the file and the way to mend it.
static IndexError damaged_index(sqlite3* db, const std::string& what) {
  const char* file = sqlite3_db_filename(db, "main");
  return IndexError(std::string(file != nullptr && *file != '\0' ? file : "the library index") + " is damaged: " + what +
                    "; rebuild it with `sandpaper library index --full`");
}

// A Weber fraction from `meta`: a number in (0, 1], else the index is damaged.
static double meta_fraction(sqlite3* db, const std::string& key, const std::string& text) {
  char* end = nullptr;
  const double w = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !(w > 0.0 && w <= 1.0))
    throw damaged_index(db, "its " + key + " is '" + text + "', not a number in (0, 1]");
  return w;
}

double Index::weber_fraction() const { return meta_fraction(db_, "weber_fraction", meta("weber_fraction")); }

WeberFractions Index::weber_fractions() const {
  WeberFractions w(weber_fraction());
  w.stiffness = meta_fraction(db_, "weber_fraction.stiffness", meta("weber_fraction.stiffness"));
  w.damping = meta_fraction(db_, "weber_fraction.damping", meta("weber_fraction.damping"));
  w.friction = meta_fraction(db_, "weber_fraction.friction", meta("weber_fraction.friction"));
  return w;
}

namespace {

const char* kEntryColumns =
    "e.name, e.family, COALESCE(f.title, ''), e.describes, e.licence, e.deprecated_by, e.file, e.library_version, e.likes, "
    "e.roughness, e.max_lateral_force_N, e.texture_kind, e.period_m, e.period_class, e.character, e.terms, e.physical, e.term_params "
    "FROM entries e LEFT JOIN families f ON f.id = e.family";

// A JSON column (written by index_write.cpp) as [name, value] pairs. The file may have been edited or
// damaged since it was written: anything else there is the index's fault, said so with the way to
// mend it, never as the JSON library's exception (docs/RELIABILITY.md, F43). `Value` is double or
// std::string.
template <class Value>
std::vector<std::pair<std::string, Value>> pairs_column(sqlite3* db, const std::string& text, const std::string& what) {
  const auto j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  std::vector<std::pair<std::string, Value>> out;
  const auto fits = [](const nlohmann::json& v) {
    if constexpr (std::is_same_v<Value, double>) return v.is_number();
    else return v.is_string();
  };
  bool ok = j.is_array();
  if (ok)
    for (const auto& kv : j) {
      if (!kv.is_array() || kv.size() != 2 || !kv[0].is_string() || !fits(kv[1])) {
        ok = false;
        break;
      }
      out.emplace_back(kv[0].get<std::string>(), kv[1].get<Value>());
    }
  if (!ok)
    throw damaged_index(db, what + " is not a JSON list of [name, " + (std::is_same_v<Value, double> ? "number" : "text") +
                                "] pairs");
  return out;
}

// `light`: the entries row only (no aliases, no other percepts), for comparing many entries.
IndexedEntry read_entry(sqlite3* db, const sql::Stmt& s, bool light = false) {
  IndexedEntry e;
  e.name = s.text(0);
  e.family = s.text(1);
  e.family_title = s.text(2);
  e.describes = s.text(3);
  e.licence = s.text(4);
  e.deprecated_by = s.text(5);
  e.file = s.text(6);
  e.library_version = s.text(7);
  for (std::size_t a = 0, b; a < s.text(8).size(); a = b + 1) {
    const auto likes = s.text(8);
    b = likes.find(' ', a);
    if (b == std::string::npos) b = likes.size();
    if (b > a) e.likes.push_back(likes.substr(a, b - a));
  }
  e.roughness = s.real(9);
  e.max_lateral_force_N = s.real(10);
  e.texture_kind = s.text(11);
  e.period_m = s.real(12);
  e.period_class = s.text(13);
  e.character = s.text(14);
  e.terms = s.text(15);
  e.physical = s.text(16);
  e.term_params = pairs_column<double>(db, s.text(17), "entry '" + e.name + "': its term_params");
  if (light) return e;
  sql::Stmt a(db, "SELECT alias FROM aliases WHERE name = ? ORDER BY rowid");
  a.bind(1, e.name);
  while (a.step()) e.aliases.push_back(a.text(0));
  sql::Stmt p(db, "SELECT percept, value FROM percepts WHERE name = ? AND percept <> 'roughness' ORDER BY rowid");
  p.bind(1, e.name);
  while (p.step()) e.others.emplace_back(p.text(0), p.real(1));
  return e;
}

}  // namespace

std::vector<IndexedEntry> Index::entries() const {
  std::vector<IndexedEntry> out;
  sql::Stmt s(db_, std::string("SELECT ") + kEntryColumns + " ORDER BY e.name");
  while (s.step()) out.push_back(read_entry(db_, s));
  return out;
}

std::optional<IndexedEntry> Index::entry(const std::string& name) const {
  sql::Stmt s(db_, std::string("SELECT ") + kEntryColumns + " WHERE e.name = ?");
  s.bind(1, name);
  if (!s.step()) return std::nullopt;
  return read_entry(db_, s);
}

std::vector<IndexedEntry> Index::entries_by_rowid(const std::vector<std::int64_t>& rowids) const {
  std::vector<IndexedEntry> out;
  sql::Stmt s(db_, std::string("SELECT ") + kEntryColumns + " WHERE e.rowid = ?");
  for (const auto id : rowids) {
    s.bind64(1, id);
    if (s.step()) out.push_back(read_entry(db_, s));
    s.reset();
  }
  return out;
}

std::vector<IndexedEntry> Index::textured_in_box(const Box& b) const {
  std::vector<IndexedEntry> out;
  std::string where =
      " JOIN coordinates c ON c.id = e.rowid WHERE c.log_force_max >= ? AND c.log_force_min <= ? AND c.log_period_max >= ? "
      "AND c.log_period_min <= ? AND c.class_max >= ? AND c.class_min <= ?";
  if (b.periodless) where += *b.periodless ? " AND c.log_period_min < -1e29" : " AND c.log_period_min >= -1e29";
  sql::Stmt s(db_, std::string("SELECT ") + kEntryColumns + where);
  s.bind(1, b.ln_force_lo).bind(2, b.ln_force_hi).bind(3, b.log2_period_lo).bind(4, b.log2_period_hi).bind(5, b.class_lo)
      .bind(6, b.class_hi);
  while (s.step()) out.push_back(read_entry(db_, s, true));
  return out;
}

double Index::texture_class(const std::string& name) const {
  sql::Stmt s(db_, "SELECT c.class_min FROM coordinates c JOIN entries e ON e.rowid = c.id WHERE e.name = ?");
  s.bind(1, name);
  return s.step() ? s.real(0) : -1;
}

double Index::class_of(const std::string& kind_terms) const {
  sql::Stmt s(db_, "SELECT id FROM classes WHERE kind_terms = ?");
  s.bind(1, kind_terms);
  return s.step() ? static_cast<double>(s.integer64(0)) : -2;
}

std::vector<IndexedEntry> Index::untextured_in_box(const LawBox& b) const {
  std::vector<IndexedEntry> out;
  sql::Stmt s(db_, std::string("SELECT ") + kEntryColumns +
                       " JOIN laws l ON l.id = e.rowid WHERE l.stiffness_max >= ? AND l.stiffness_min <= ? AND "
                       "l.damping_max >= ? AND l.damping_min <= ? AND l.friction_max >= ? AND l.friction_min <= ? AND "
                       "l.class_max >= ? AND l.class_min <= ?");
  for (std::size_t d = 0; d < 3; ++d) s.bind(static_cast<int>(1 + 2 * d), b.lo[d]).bind(static_cast<int>(2 + 2 * d), b.hi[d]);
  s.bind(7, b.class_lo).bind(8, b.class_hi);
  while (s.step()) out.push_back(read_entry(db_, s, true));
  return out;
}

std::vector<IndexedEntry> Index::untextured() const {
  std::vector<IndexedEntry> out;
  sql::Stmt s(db_, std::string("SELECT ") + kEntryColumns + " WHERE e.max_lateral_force_N <= 0");
  while (s.step()) out.push_back(read_entry(db_, s, true));
  return out;
}

std::size_t Index::size() const {
  sql::Stmt s(db_, "SELECT count(*) FROM entries");
  return s.step() ? static_cast<std::size_t>(s.integer64(0)) : 0;
}

std::optional<std::string> Index::resolve(const std::string& name) const {
  sql::Stmt s(db_, "SELECT name FROM entries WHERE name = ? UNION ALL SELECT name FROM aliases WHERE alias = ?");
  s.bind(1, name).bind(2, name);
  if (!s.step()) return std::nullopt;
  return s.text(0);
}

std::vector<std::string> Index::names_and_aliases() const {
  std::vector<std::string> out;
  sql::Stmt s(db_, "SELECT name FROM entries UNION SELECT alias FROM aliases");
  while (s.step()) out.push_back(s.text(0));
  return out;
}

std::vector<std::string> Index::stimulus_families() const {
  std::vector<std::string> out;
  sql::Stmt s(db_, "SELECT id FROM families WHERE stimulus_set != 0 ORDER BY ord");
  while (s.step()) out.push_back(s.text(0));
  return out;
}

std::vector<std::string> Index::families() const {
  std::vector<std::string> out;
  sql::Stmt s(db_, "SELECT id FROM families ORDER BY ord");
  while (s.step()) out.push_back(s.text(0));
  return out;
}

std::vector<IndexedStatement> Index::statements(const std::string& name) const {
  std::vector<IndexedStatement> out;
  sql::Stmt s(db_, "SELECT ordinal, line, keyword, text FROM statements WHERE name = ? ORDER BY ordinal");
  sql::Stmt src(db_, "SELECT kind, text FROM sources WHERE name = ? AND ordinal = ? ORDER BY rowid");
  s.bind(1, name);
  while (s.step()) {
    IndexedStatement st{s.integer(1), s.text(2), s.text(3), {}};
    src.bind(1, name).bind(2, s.integer(0));
    while (src.step()) st.sources.emplace_back(src.text(0), src.text(1));
    src.reset();
    out.push_back(std::move(st));
  }
  return out;
}

std::vector<IndexedProvenance> Index::provenance(const std::string& name) const {
  std::vector<IndexedProvenance> out;
  sql::Stmt s(db_, "SELECT parameter, value_si, si_unit, stated, layer, source, notes FROM provenance WHERE name = ? ORDER BY ordinal");
  s.bind(1, name);
  while (s.step()) {
    IndexedProvenance p{s.text(0), s.real(1), s.text(2), s.text(3), s.text(4), s.text(5), {}};
    p.notes = pairs_column<std::string>(db_, s.text(6), "entry '" + name + "': the notes of its " + p.parameter);
    out.push_back(std::move(p));
  }
  return out;
}

std::vector<std::pair<std::string, double>> Index::full_text(const std::string& q) const {
  std::vector<std::pair<std::string, double>> out;
  // bm25 weights: a word in the name or an alias counts more than one in the description or family.
  sql::Stmt s(db_, "SELECT name, bm25(search, 10.0, 8.0, 4.0, 2.0) AS rank FROM search WHERE search MATCH ? ORDER BY rank, name");
  s.bind(1, q);
  while (s.step()) out.emplace_back(s.text(0), s.real(1));
  return out;
}

std::vector<WordFields> Index::word_candidates(const std::vector<std::string>& words) const {
  // The search table's text holds every field (the family's with its title and describes), so a
  // substring test in SQLite narrows the rows before word_score() reads them; lower() folds ASCII,
  // as search_tokens() does.
  std::string text =
      "SELECT e.name, s.aliases, e.describes, e.family, COALESCE(f.title, '') FROM search s JOIN entries e ON e.rowid = s.rowid "
      "LEFT JOIN families f ON f.id = e.family WHERE 1";
  for (std::size_t i = 0; i < words.size(); ++i)
    text += " AND instr(lower(s.name || ' ' || s.aliases || ' ' || s.describes || ' ' || s.family), ?" + std::to_string(i + 1) + ") > 0";
  text += " ORDER BY e.name";
  sql::Stmt s(db_, text);
  for (std::size_t i = 0; i < words.size(); ++i) s.bind(static_cast<int>(i + 1), words[i]);
  std::vector<WordFields> out;
  while (s.step()) {
    WordFields f{s.text(0), {}, s.text(2), s.text(3), s.text(4)};
    for (auto& a : search_tokens(s.text(1))) f.aliases.push_back(std::move(a));
    out.push_back(std::move(f));
  }
  return out;
}

std::vector<std::filesystem::path> edited_inputs(const Index& index, const std::filesystem::path& library_dir,
                                                 const std::vector<std::string>& names) {
  // The entries compiling them reads, then the library files each of those records.
  std::set<std::string> targets;
  sql::Stmt of_file(index.handle(), "SELECT name FROM entries WHERE file = ?");
  sql::Stmt files(index.handle(), "SELECT target FROM depends WHERE name = ? AND kind = 'file'");
  std::vector<std::string> reached_names = names;
  for (const auto& f : index.files_reached(names)) {
    of_file.bind(1, f);
    while (of_file.step()) reached_names.push_back(of_file.text(0));
    of_file.reset();
  }
  for (const auto& n : reached_names) {
    files.bind(1, n);
    while (files.step()) targets.insert(files.text(0));
    files.reset();
  }
  std::vector<std::filesystem::path> out;
  for (const auto& rel : stamps::edited(index.handle(), {{"library", library_dir}}, {targets.begin(), targets.end()}))
    if (rel.rfind("library/", 0) == 0) out.push_back(library_dir / rel.substr(8));
  return out;
}

IndexState root_index_state(const std::filesystem::path& index_path, const std::filesystem::path& library_dir,
                            const std::filesystem::path& calibration_dir) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(index_path, ec)) return IndexState::Missing;
  try {
    Index idx(index_path);
    if (idx.meta("library_dir") != std::filesystem::absolute(library_dir).lexically_normal().string()) return IndexState::Stale;
    if (!stamps::unchanged(idx.handle(), {{"library", library_dir}, {"calibration", calibration_dir}})) return IndexState::Stale;
    return IndexState::Fresh;
  } catch (const std::exception&) {
    return IndexState::Stale;
  }
}

std::vector<std::pair<std::string, std::string>> Index::input_hashes() const {
  std::vector<std::pair<std::string, std::string>> out;
  sql::Stmt s(db_, "SELECT name, hash FROM inputs ORDER BY name");
  while (s.step()) out.emplace_back(s.text(0), s.text(1));
  return out;
}

std::optional<std::string> Index::input_hash(const std::string& name) const {
  sql::Stmt s(db_, "SELECT hash FROM inputs WHERE name = ?");
  s.bind(1, name);
  if (!s.step()) return std::nullopt;
  return s.text(0);
}

std::vector<std::string> Index::files_reached(const std::vector<std::string>& names) const {
  std::vector<std::string> roots = names, links;
  if (const auto ref = meta("library_reference"); !ref.empty()) roots.push_back(ref);
  sql::Stmt d(db_, "SELECT deprecated_by FROM entries WHERE name = ? AND deprecated_by <> ''");
  for (const auto& n : names) {
    d.bind(1, n);
    if (d.step()) links.push_back(d.text(0));
    d.reset();
  }
  const auto files = curation::files_reached(
      db_, roots, links, [](const std::string&) { return std::optional<ReachedEntry>(); },
      [](const std::string&) { return false; });
  return {files.begin(), files.end()};
}

}  // namespace sandpaper::curation
