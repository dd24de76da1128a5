#include "record.hpp"

#include <sqlite3.h>

#include <stdexcept>

#include <nlohmann/json.hpp>

namespace sandpaper::catalog {

namespace {

constexpr const char* kSchema =
    "CREATE TABLE IF NOT EXISTS meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);"
    "CREATE TABLE IF NOT EXISTS entries(name TEXT PRIMARY KEY, hash TEXT NOT NULL, family TEXT NOT NULL,"
    " describes TEXT NOT NULL, licence TEXT NOT NULL, deprecated_by TEXT NOT NULL, aliases TEXT NOT NULL,"
    " roughness REAL, max_lateral_force_N REAL NOT NULL, page TEXT NOT NULL, thumbnail TEXT NOT NULL, files TEXT NOT NULL,"
    " period_m REAL NOT NULL, kind TEXT NOT NULL, source_kinds INTEGER NOT NULL, root TEXT NOT NULL);";

void check(sqlite3* db, int rc, const char* what) {
  if (rc != SQLITE_OK && rc != SQLITE_DONE && rc != SQLITE_ROW)
    throw std::runtime_error(std::string("catalog record: ") + what + ": " + (db ? sqlite3_errmsg(db) : sqlite3_errstr(rc)));
}

void exec(sqlite3* db, const char* sql) { check(db, sqlite3_exec(db, sql, nullptr, nullptr, nullptr), sql); }

std::string text(sqlite3_stmt* s, int col) {
  const auto* p = sqlite3_column_text(s, col);
  return p ? reinterpret_cast<const char*>(p) : "";
}

struct Stmt {
  sqlite3_stmt* s = nullptr;
  Stmt(sqlite3* db, const char* sql) { check(db, sqlite3_prepare_v2(db, sql, -1, &s, nullptr), sql); }
  ~Stmt() { sqlite3_finalize(s); }
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;
};

void bind_text(sqlite3_stmt* s, int i, const std::string& v) { sqlite3_bind_text(s, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT); }

// The next row (true), or the end (false). Anything else (a damaged file: SQLITE_CORRUPT partway)
// throws: a reader that stopped there would take the rows before the damage for the whole record,
// or a row it could not read for an entry the record does not have.
bool next_row(sqlite3* db, sqlite3_stmt* s) {
  const int rc = sqlite3_step(s);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  throw std::runtime_error(std::string("catalog record: ") + sqlite3_errmsg(db));
}

}  // namespace

bool plain_file_name(std::string_view name) {
  return !name.empty() && name[0] != '.' && name.find_first_of(std::string_view("/\\\0", 3)) == std::string_view::npos;
}

std::optional<std::vector<std::string>> RecordedEntry::files() const {
  if (files_json.empty()) return std::vector<std::string>{};
  const auto j = nlohmann::json::parse(files_json, nullptr, false);
  if (!j.is_array()) return std::nullopt;
  std::vector<std::string> out;
  for (const auto& f : j) {
    if (!f.is_string()) return std::nullopt;
    auto name = f.get<std::string>();
    if (!plain_file_name(name)) return std::nullopt;
    out.push_back(std::move(name));
  }
  return out;
}

namespace {

// Opens the record in `dir` if it was drawn with `settings`; nullptr otherwise. Read-write: opening
// rolls back a transaction that a killed run left in the journal.
sqlite3* open_record(const std::filesystem::path& dir, const std::string& settings) {
  std::error_code ec;
  const auto file = dir / kRecordFile;
  if (!std::filesystem::is_regular_file(file, ec)) return nullptr;
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    return nullptr;
  }
  try {
    sqlite3_busy_timeout(db, 10'000);
    Stmt m(db, "SELECT value FROM meta WHERE key = 'settings'");
    if (sqlite3_step(m.s) == SQLITE_ROW && text(m.s, 0) == settings) return db;
  } catch (const std::exception&) {
  }
  sqlite3_close(db);
  return nullptr;
}

struct Closer {
  sqlite3* db;
  ~Closer() { sqlite3_close(db); }
};

RecordedEntry entry_of(sqlite3_stmt* s) {
  RecordedEntry e;
  e.hash = text(s, 1);
  auto& r = e.row;
  r.name = text(s, 0);
  r.family = text(s, 2);
  r.describes = text(s, 3);
  r.licence = text(s, 4);
  r.deprecated_by = text(s, 5);
  if (const auto a = text(s, 6); a != "[]") r.aliases = nlohmann::json::parse(a).get<std::vector<std::string>>();
  if (sqlite3_column_type(s, 7) != SQLITE_NULL) r.roughness = sqlite3_column_double(s, 7);
  r.max_lateral_force_N = sqlite3_column_double(s, 8);
  r.page = text(s, 9);
  r.thumbnail = text(s, 10);
  e.files_json = text(s, 11);
  r.period_m = sqlite3_column_double(s, 12);
  r.kind = text(s, 13);
  r.source_kinds = static_cast<unsigned>(sqlite3_column_int64(s, 14));
  r.root = text(s, 15);
  return e;
}

constexpr const char* kColumns =
    "SELECT name, hash, family, describes, licence, deprecated_by, aliases, roughness, max_lateral_force_N, page, thumbnail, files, "
    "period_m, kind, source_kinds, root FROM entries";

}  // namespace

std::optional<Record> read_record(const std::filesystem::path& dir, const std::string& settings, const std::vector<std::string>* only) {
  sqlite3* db = open_record(dir, settings);
  if (!db) return std::nullopt;
  Closer closer{db};
  Record out;
  try {
    if (only) {
      Stmt s(db, (std::string(kColumns) + " WHERE name = ?").c_str());
      for (const auto& name : *only) {
        bind_text(s.s, 1, name);
        if (next_row(db, s.s)) out.emplace(name, entry_of(s.s));
        sqlite3_reset(s.s);
      }
      return out;
    }
    {
      Stmt n(db, "SELECT count(*) FROM entries");
      if (sqlite3_step(n.s) == SQLITE_ROW) out.reserve(static_cast<std::size_t>(sqlite3_column_int64(n.s, 0)));
    }
    Stmt s(db, kColumns);
    while (next_row(db, s.s)) {
      auto e = entry_of(s.s);
      auto key = e.row.name;
      out.emplace(std::move(key), std::move(e));
    }
  } catch (const std::exception&) {
    return std::nullopt;  // not a record of this program: draw everything
  }
  return out;
}

std::optional<std::unordered_map<std::string, std::string>> read_record_hashes(const std::filesystem::path& dir,
                                                                               const std::string& settings,
                                                                               const std::vector<std::string>* only) {
  sqlite3* db = open_record(dir, settings);
  if (!db) return std::nullopt;
  Closer closer{db};
  std::unordered_map<std::string, std::string> out;
  try {
    if (only) {
      Stmt s(db, "SELECT hash FROM entries WHERE name = ?");
      for (const auto& name : *only) {
        bind_text(s.s, 1, name);
        if (next_row(db, s.s)) out.emplace(name, text(s.s, 0));
        sqlite3_reset(s.s);
      }
      return out;
    }
    {
      Stmt n(db, "SELECT count(*) FROM entries");
      if (sqlite3_step(n.s) == SQLITE_ROW) out.reserve(static_cast<std::size_t>(sqlite3_column_int64(n.s, 0)));
    }
    Stmt s(db, "SELECT name, hash FROM entries");
    while (next_row(db, s.s)) out.emplace(text(s.s, 0), text(s.s, 1));
  } catch (const std::exception&) {
    return std::nullopt;
  }
  return out;
}

std::string recorded_index_fingerprint(const std::filesystem::path& dir, const std::string& settings) {
  sqlite3* db = open_record(dir, settings);
  if (!db) return "";
  Closer closer{db};
  try {
    Stmt m(db, "SELECT value FROM meta WHERE key = 'index_fingerprint'");
    if (sqlite3_step(m.s) == SQLITE_ROW) return text(m.s, 0);
  } catch (const std::exception&) {
  }
  return "";
}

RecordWriter::RecordWriter(const std::filesystem::path& file, const std::string& settings) {
  if (sqlite3_open_v2(file.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
    const std::string why = sqlite3_errmsg(db_);
    sqlite3_close(db_);
    throw std::runtime_error("cannot open " + file.string() + ": " + why);
  }
  sqlite3_busy_timeout(db_, 10'000);
  exec(db_, "PRAGMA journal_mode = DELETE; PRAGMA synchronous = FULL; BEGIN IMMEDIATE");
  open_ = true;
  exec(db_, kSchema);
  Stmt m(db_, "INSERT OR REPLACE INTO meta VALUES ('settings', ?)");
  bind_text(m.s, 1, settings);
  check(db_, sqlite3_step(m.s), "settings");
}

RecordWriter::~RecordWriter() {
  if (open_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  sqlite3_close(db_);
}

void RecordWriter::put(const std::string& name, const RecordedEntry& e) {
  Stmt s(db_, "INSERT OR REPLACE INTO entries VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  const auto& r = e.row;
  bind_text(s.s, 1, name);
  bind_text(s.s, 2, e.hash);
  bind_text(s.s, 3, r.family);
  bind_text(s.s, 4, r.describes);
  bind_text(s.s, 5, r.licence);
  bind_text(s.s, 6, r.deprecated_by);
  bind_text(s.s, 7, nlohmann::json(r.aliases).dump());
  if (r.roughness) sqlite3_bind_double(s.s, 8, *r.roughness);
  sqlite3_bind_double(s.s, 9, r.max_lateral_force_N);
  bind_text(s.s, 10, r.page);
  bind_text(s.s, 11, r.thumbnail);
  bind_text(s.s, 12, e.files_json);
  sqlite3_bind_double(s.s, 13, r.period_m);
  bind_text(s.s, 14, r.kind);
  sqlite3_bind_int64(s.s, 15, r.source_kinds);
  bind_text(s.s, 16, r.root);
  check(db_, sqlite3_step(s.s), "put");
}

void RecordWriter::erase(const std::string& name) {
  Stmt s(db_, "DELETE FROM entries WHERE name = ?");
  bind_text(s.s, 1, name);
  check(db_, sqlite3_step(s.s), "erase");
}

void RecordWriter::set_index_fingerprint(const std::string& fingerprint) {
  Stmt s(db_, "INSERT OR REPLACE INTO meta VALUES ('index_fingerprint', ?)");
  bind_text(s.s, 1, fingerprint);
  check(db_, sqlite3_step(s.s), "index fingerprint");
}

void RecordWriter::commit() {
  exec(db_, "COMMIT");
  open_ = false;
}

}  // namespace sandpaper::catalog
