#pragma once
// Small RAII over the SQLite C API for the index (internal to sandpaper_curation).
#include <sqlite3.h>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace sandpaper::curation::sql {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline void exec(sqlite3* db, const std::string& sql) {
  char* err = nullptr;
  if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
    std::string msg = err ? err : sqlite3_errmsg(db);
    sqlite3_free(err);
    throw Error("SQLite: " + msg);
  }
}

class Stmt {
 public:
  Stmt(sqlite3* db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &s_, nullptr) != SQLITE_OK)
      throw Error("SQLite: " + std::string(sqlite3_errmsg(db)) + " in: " + sql);
  }
  ~Stmt() { sqlite3_finalize(s_); }
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;

  Stmt& bind(int i, const std::string& v) {
    check(sqlite3_bind_text(s_, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT));
    return *this;
  }
  Stmt& bind(int i, double v) {
    check(sqlite3_bind_double(s_, i, v));
    return *this;
  }
  Stmt& bind(int i, int v) {
    check(sqlite3_bind_int(s_, i, v));
    return *this;
  }
  Stmt& bind64(int i, std::int64_t v) {
    check(sqlite3_bind_int64(s_, i, static_cast<sqlite3_int64>(v)));
    return *this;
  }
  // True while there is a row.
  bool step() {
    const int rc = sqlite3_step(s_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw Error("SQLite: " + std::string(sqlite3_errmsg(db_)));
  }
  void run() {
    step();
    reset();
  }
  void reset() {
    sqlite3_reset(s_);
    sqlite3_clear_bindings(s_);
  }
  std::string text(int col) const {
    const auto* t = sqlite3_column_text(s_, col);
    return t ? std::string(reinterpret_cast<const char*>(t), static_cast<std::size_t>(sqlite3_column_bytes(s_, col))) : std::string();
  }
  double real(int col) const { return sqlite3_column_double(s_, col); }
  int integer(int col) const { return sqlite3_column_int(s_, col); }
  std::int64_t integer64(int col) const { return static_cast<std::int64_t>(sqlite3_column_int64(s_, col)); }

 private:
  void check(int rc) {
    if (rc != SQLITE_OK) throw Error("SQLite: " + std::string(sqlite3_errmsg(db_)));
  }
  sqlite3* db_;
  sqlite3_stmt* s_ = nullptr;
};

}  // namespace sandpaper::curation::sql
