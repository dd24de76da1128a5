#include "stamps.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iterator>
#include <type_traits>

#include "sqlite_util.hpp"

namespace sandpaper::curation::stamps {

namespace {

struct Stat {
  bool ok = false, directory = false, regular = false;
  std::int64_t size = 0, mtime_ns = 0;
};

Stat stat_of(const std::filesystem::path& p) {
  struct ::stat st {};
  Stat s;
  if (::stat(p.c_str(), &st) != 0) return s;
  s.ok = true;
  s.directory = S_ISDIR(st.st_mode);
  s.regular = S_ISREG(st.st_mode);
  s.size = static_cast<std::int64_t>(st.st_size);
  s.mtime_ns = static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1'000'000'000 + st.st_mtim.tv_nsec;
  return s;
}

std::uint64_t fnv(const char* p, std::size_t n, std::uint64_t h = 1469598103934665603ULL) {
  for (std::size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(p[i]);
    h *= 1099511628211ULL;
  }
  return h;
}

std::string hex(std::uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

// An unreadable file hashes as "unreadable": the compile that reads it reports why.
std::string hash_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return "unreadable";
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return hex(fnv(bytes.data(), bytes.size()));
}

bool hidden(const std::filesystem::path& p) {
  const auto name = p.filename().string();
  return !name.empty() && name[0] == '.';
}

std::string folder_of(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash);
}

}  // namespace

std::int64_t now_ns() {
  timespec ts{};
  ::clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::string fnv_hex(const std::string& bytes) { return hex(fnv(bytes.data(), bytes.size())); }

void walk(const std::filesystem::path& dir, const std::string& tag, const std::map<std::string, FileStamp>& known,
          std::int64_t build_start_ns, bool every_file_checked, Tree& into) {
  const std::int64_t racy_after = build_start_ns - kRacyWindowNs;
  auto add_folder = [&](const std::filesystem::path& p, const std::string& rel) {
    const auto s = stat_of(p);
    // The root's own files (library.toml) are always stat'ed: the root is one folder, and the
    // manifest is what an in-place edit most often touches.
    into.folders.push_back({rel, s.mtime_ns, every_file_checked || rel == tag || s.mtime_ns > racy_after});
  };
  add_folder(dir, tag);
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec); !ec && it != std::filesystem::recursive_directory_iterator();
       it.increment(ec)) {
    if (hidden(it->path())) {
      if (it->is_directory(ec)) it.disable_recursion_pending();
      continue;
    }
    const std::string rel = tag + "/" + it->path().lexically_relative(dir).generic_string();
    const auto s = stat_of(it->path());
    if (s.directory) {
      add_folder(it->path(), rel);
      continue;
    }
    if (!s.regular) continue;
    FileStamp f{rel, folder_of(rel), s.size, s.mtime_ns, {}, s.mtime_ns > racy_after};
    const auto k = known.find(rel);
    if (k != known.end() && !k->second.racy && k->second.size == s.size && k->second.mtime_ns == s.mtime_ns) {
      f.hash = k->second.hash;
    } else {
      f.hash = hash_file(it->path());
      ++into.hashed;
    }
    into.files.push_back(std::move(f));
  }
  std::sort(into.files.begin(), into.files.end(), [](const auto& a, const auto& b) { return a.path < b.path; });
}

void write(sqlite3* db, const Tree& tree) {
  sql::exec(db,
            "DROP TABLE IF EXISTS files; DROP TABLE IF EXISTS folders;"
            "CREATE TABLE files(path TEXT PRIMARY KEY, folder TEXT NOT NULL, size INTEGER NOT NULL, mtime_ns INTEGER NOT NULL,"
            "  hash TEXT NOT NULL, racy INTEGER NOT NULL);"
            "CREATE INDEX files_folder ON files(folder);"
            "CREATE TABLE folders(path TEXT PRIMARY KEY, mtime_ns INTEGER NOT NULL, files_checked INTEGER NOT NULL);");
  sql::Stmt f(db, "INSERT INTO files VALUES (?, ?, ?, ?, ?, ?)");
  for (const auto& x : tree.files)
    f.bind(1, x.path).bind(2, x.folder).bind64(3, x.size).bind64(4, x.mtime_ns).bind(5, x.hash).bind(6, x.racy ? 1 : 0).run();
  sql::Stmt d(db, "INSERT INTO folders VALUES (?, ?, ?)");
  for (const auto& x : tree.folders) d.bind(1, x.path).bind64(2, x.mtime_ns).bind(3, x.files_checked ? 1 : 0).run();
}

void update(sqlite3* db, const Tree& tree, const std::map<std::string, FileStamp>& known) {
  sql::Stmt put(db, "INSERT OR REPLACE INTO files VALUES (?, ?, ?, ?, ?, ?)");
  std::size_t kept = 0;
  for (const auto& x : tree.files) {
    const auto k = known.find(x.path);
    if (k != known.end()) {
      ++kept;
      const auto& o = k->second;
      if (o.size == x.size && o.mtime_ns == x.mtime_ns && o.hash == x.hash && o.racy == x.racy) continue;
    }
    put.bind(1, x.path).bind(2, x.folder).bind64(3, x.size).bind64(4, x.mtime_ns).bind(5, x.hash).bind(6, x.racy ? 1 : 0).run();
  }
  if (kept != known.size()) {
    sql::Stmt del(db, "DELETE FROM files WHERE path = ?");
    for (const auto& [path, stamp] : known)
      if (!std::binary_search(tree.files.begin(), tree.files.end(), path,
                              [](const auto& a, const auto& b) {
                                if constexpr (std::is_same_v<std::decay_t<decltype(a)>, std::string>) return a < b.path;
                                else return a.path < b;
                              }))
        del.bind(1, path).run();
  }
  sql::exec(db, "DELETE FROM folders");
  sql::Stmt d(db, "INSERT INTO folders VALUES (?, ?, ?)");
  for (const auto& x : tree.folders) d.bind(1, x.path).bind64(2, x.mtime_ns).bind(3, x.files_checked ? 1 : 0).run();
}

bool same(sqlite3* db, const Tree& tree, const std::map<std::string, FileStamp>& known) {
  if (tree.files.size() != known.size()) return false;
  auto k = known.begin();  // both sorted by path
  for (const auto& x : tree.files) {
    const auto& o = (k++)->second;
    if (o.path != x.path || o.size != x.size || o.mtime_ns != x.mtime_ns || o.hash != x.hash || o.racy != x.racy) return false;
  }
  std::map<std::string, std::pair<std::int64_t, bool>> folders;
  sql::Stmt s(db, "SELECT path, mtime_ns, files_checked FROM folders");
  while (s.step()) folders[s.text(0)] = {s.integer64(1), s.integer(2) != 0};
  if (folders.size() != tree.folders.size()) return false;
  for (const auto& f : tree.folders) {
    const auto it = folders.find(f.path);
    if (it == folders.end() || it->second != std::make_pair(f.mtime_ns, f.files_checked)) return false;
  }
  return true;
}

std::map<std::string, FileStamp> read_files(sqlite3* db) {
  std::map<std::string, FileStamp> out;
  try {
    sql::Stmt s(db, "SELECT path, folder, size, mtime_ns, hash, racy FROM files");
    while (s.step()) out[s.text(0)] = {s.text(0), s.text(1), s.integer64(2), s.integer64(3), s.text(4), s.integer(5) != 0};
  } catch (const sql::Error&) {
    return {};  // an index of an older schema: everything is hashed
  }
  return out;
}

bool unchanged(sqlite3* db, const std::map<std::string, std::filesystem::path>& roots) {
  auto on_disk = [&](const std::string& rel) -> std::filesystem::path {
    const auto slash = rel.find('/');
    const auto root = roots.find(rel.substr(0, slash));
    if (root == roots.end()) return {};
    return slash == std::string::npos ? root->second : root->second / rel.substr(slash + 1);
  };
  sql::Stmt folders(db, "SELECT path, mtime_ns, files_checked FROM folders");
  sql::Stmt files(db, "SELECT path, size, mtime_ns, hash, racy FROM files WHERE folder = ?");
  std::size_t seen = 0;
  while (folders.step()) {
    ++seen;
    const auto dir = on_disk(folders.text(0));
    const auto s = stat_of(dir);
    if (dir.empty() || !s.directory || s.mtime_ns != folders.integer64(1)) return false;
    if (folders.integer(2) == 0) continue;
    // Every file of this folder keeps its stamp, and no file came or went.
    std::map<std::string, Stat> present;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
      if (hidden(e.path())) continue;
      const auto fs = stat_of(e.path());
      if (fs.regular) present[folders.text(0) + "/" + e.path().filename().string()] = fs;
    }
    if (ec) return false;
    files.bind(1, folders.text(0));
    std::size_t recorded = 0;
    while (files.step()) {
      ++recorded;
      const auto p = present.find(files.text(0));
      if (p == present.end() || p->second.size != files.integer64(1) || p->second.mtime_ns != files.integer64(2)) return false;
      if (files.integer(4) != 0 && hash_file(on_disk(files.text(0))) != files.text(3)) return false;
    }
    files.reset();
    if (recorded != present.size()) return false;
  }
  return seen > 0;
}

}  // namespace sandpaper::curation::stamps
