#include "stamps.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iterator>
#include <string_view>

#include "sandpaper/curation/index.hpp"
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

// An unreadable file hashes as "unreadable": the compile that reads it reports why. Takes `fd`.
std::string hash_fd(int fd) {
  if (fd < 0) return "unreadable";
  std::uint64_t h = 1469598103934665603ULL;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0) {
      ::close(fd);
      return "unreadable";
    }
    if (n == 0) break;
    h = fnv(buf, static_cast<std::size_t>(n), h);
  }
  ::close(fd);
  return hex(h);
}

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

// The entry name an entry file would give ("corduroy" for "library/textiles/corduroy.hmat"), else
// "": kept in `files` so that an update told which files changed finds a second file with a
// name without reading every path.
std::string stem_of(const std::string& path) {
  constexpr std::string_view ext = ".hmat";
  if (path.rfind("library/", 0) != 0 || path.size() < ext.size() || path.compare(path.size() - ext.size(), ext.size(), ext) != 0)
    return {};
  const auto slash = path.rfind('/');
  return path.substr(slash + 1, path.size() - ext.size() - slash - 1);
}

constexpr const char* kPutFile = "INSERT OR REPLACE INTO files VALUES (?, ?, ?, ?, ?, ?, ?)";
void put_file(sql::Stmt& put, const FileStamp& x) {
  put.bind(1, x.path).bind(2, x.folder).bind64(3, x.size).bind64(4, x.mtime_ns).bind(5, x.hash).bind(6, x.racy ? 1 : 0).bind(7, stem_of(x.path)).run();
}

std::uint64_t line_hash(const FileStamp& f) {
  const std::string line = f.path + " " + f.hash;
  return fnv(line.data(), line.size());
}

std::uint64_t from_hex(const std::string& h) { return std::strtoull(h.c_str(), nullptr, 16); }

// The parent of a tagged path ("library/a/b.hmat" -> "library/a"), or "" for a root.
std::string parent_of(const std::string& path) {
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

std::string fingerprint(const std::vector<FileStamp>& files) {
  const std::string head = "sandpaper-library-index/" + std::to_string(kIndexSchemaVersion);
  std::uint64_t sum = fnv(head.data(), head.size());
  for (const auto& f : files) sum += line_hash(f);
  return hex(sum);
}

std::string fingerprint_update(const std::string& old, const std::vector<FileStamp>& removed, const std::vector<FileStamp>& added) {
  std::uint64_t sum = from_hex(old);
  for (const auto& f : removed) sum -= line_hash(f);
  for (const auto& f : added) sum += line_hash(f);
  return hex(sum);
}

const FileStamp* find(const Known& known, const std::string& path) {
  const auto it = std::lower_bound(known.begin(), known.end(), path, [](const FileStamp& f, const std::string& p) { return f.path < p; });
  return it != known.end() && it->path == path ? &*it : nullptr;
}

namespace {

struct Walk {
  const Known& known;
  std::size_t cursor;  // into `known`: files come in path order, so each lookup moves it forward
  std::int64_t racy_after;
  bool every_file_checked;
  Tree& into;
};

// One folder of a walk, by its open descriptor: readdir and fstatat relative to it, so that no
// path is resolved from the root again. Its entries are taken in the order their paths sort
// (a folder "a" as "a/"), so the files come out sorted and are matched against the recorded
// stamps by one forward pass: at 100,000 files, std::filesystem's iterator, full-path stat, a
// binary search per file and a sort at the end took 0.8 s, of which the string compares were most.
void walk_folder(int dfd, const std::string& rel, Walk& w) {
  DIR* d = ::fdopendir(dfd);
  if (!d) {
    ::close(dfd);
    return;
  }
  struct Item {
    std::string key, name;
    struct ::stat st;
    bool enter;
  };
  std::vector<Item> items;
  while (const dirent* e = ::readdir(d)) {
    const char* name = e->d_name;
    if (name[0] == '.') continue;  // hidden, and . and ..
    Item it{name, name, {}, false};
    if (::fstatat(dfd, name, &it.st, 0) != 0) continue;
    if (S_ISDIR(it.st.st_mode)) {
      it.key += '/';
      // A link to a folder is stamped but not entered, as the library's own scan does not enter it.
      bool link = e->d_type == DT_LNK;
      if (e->d_type == DT_UNKNOWN) {
        struct ::stat lst {};
        link = ::fstatat(dfd, name, &lst, AT_SYMLINK_NOFOLLOW) == 0 && S_ISLNK(lst.st_mode);
      }
      it.enter = !link;
    } else if (!S_ISREG(it.st.st_mode)) {
      continue;
    }
    items.push_back(std::move(it));
  }
  std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.key < b.key; });
  for (auto& it : items) {
    std::string path = rel + "/" + it.name;
    const std::int64_t mtime = static_cast<std::int64_t>(it.st.st_mtim.tv_sec) * 1'000'000'000 + it.st.st_mtim.tv_nsec;
    if (S_ISDIR(it.st.st_mode)) {
      w.into.folders.push_back({path, mtime, w.every_file_checked || mtime > w.racy_after});
      if (!it.enter) continue;
      const int sub = ::openat(dfd, it.name.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      if (sub >= 0) walk_folder(sub, path, w);
      continue;
    }
    FileStamp f{std::move(path), rel, static_cast<std::int64_t>(it.st.st_size), mtime, {}, mtime > w.racy_after};
    while (w.cursor < w.known.size() && w.known[w.cursor].path < f.path) ++w.cursor;
    const FileStamp* k = w.cursor < w.known.size() && w.known[w.cursor].path == f.path ? &w.known[w.cursor] : nullptr;
    if (k && !k->racy && k->size == f.size && k->mtime_ns == f.mtime_ns) {
      f.hash = k->hash;
    } else {
      f.hash = hash_fd(::openat(dfd, it.name.c_str(), O_RDONLY | O_CLOEXEC));
      ++w.into.hashed;
    }
    w.into.files.push_back(std::move(f));
  }
  ::closedir(d);
}

}  // namespace

void walk(const std::filesystem::path& dir, const std::string& tag, const Known& known, std::int64_t build_start_ns,
          bool every_file_checked, Tree& into) {
  const auto s = stat_of(dir);
  into.folders.push_back({tag, s.mtime_ns, true});
  const auto first = std::lower_bound(known.begin(), known.end(), tag, [](const FileStamp& f, const std::string& t) { return f.path < t; });
  Walk w{known, static_cast<std::size_t>(first - known.begin()), build_start_ns - kRacyWindowNs, every_file_checked, into};
  const std::size_t before = into.files.size();
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) walk_folder(fd, tag, w);
  // Each walk's files are sorted; a second tag's go in among the first's.
  const auto by_path = [](const FileStamp& a, const FileStamp& b) { return a.path < b.path; };
  std::inplace_merge(into.files.begin(), into.files.begin() + static_cast<std::ptrdiff_t>(before), into.files.end(), by_path);
}

void write(sqlite3* db, const Tree& tree) {
  sql::exec(db,
            "DROP TABLE IF EXISTS files; DROP TABLE IF EXISTS folders;"
            "CREATE TABLE files(path TEXT PRIMARY KEY, folder TEXT NOT NULL, size INTEGER NOT NULL, mtime_ns INTEGER NOT NULL,"
            "  hash TEXT NOT NULL, racy INTEGER NOT NULL, stem TEXT NOT NULL);"
            "CREATE INDEX files_folder ON files(folder);"
            "CREATE INDEX files_stem ON files(stem) WHERE stem <> '';"
            "CREATE TABLE folders(path TEXT PRIMARY KEY, mtime_ns INTEGER NOT NULL, files_checked INTEGER NOT NULL);");
  sql::Stmt f(db, kPutFile);
  for (const auto& x : tree.files) put_file(f, x);
  sql::Stmt d(db, "INSERT INTO folders VALUES (?, ?, ?)");
  for (const auto& x : tree.folders) d.bind(1, x.path).bind64(2, x.mtime_ns).bind(3, x.files_checked ? 1 : 0).run();
}

void update(sqlite3* db, const Tree& tree, const Known& known) {
  sql::Stmt put(db, kPutFile);
  std::size_t kept = 0;
  for (const auto& x : tree.files) {
    if (const auto* k = find(known, x.path)) {
      ++kept;
      const auto& o = *k;
      if (o.size == x.size && o.mtime_ns == x.mtime_ns && o.hash == x.hash && o.racy == x.racy) continue;
    }
    put_file(put, x);
  }
  if (kept != known.size()) {
    sql::Stmt del(db, "DELETE FROM files WHERE path = ?");
    for (const auto& k : known)
      if (!find(tree.files, k.path)) del.bind(1, k.path).run();
  }
  sql::exec(db, "DELETE FROM folders");
  sql::Stmt d(db, "INSERT INTO folders VALUES (?, ?, ?)");
  for (const auto& x : tree.folders) d.bind(1, x.path).bind64(2, x.mtime_ns).bind(3, x.files_checked ? 1 : 0).run();
}

bool same(sqlite3* db, const Tree& tree, const Known& known) {
  if (tree.files.size() != known.size()) return false;
  auto k = known.begin();  // both sorted by path
  for (const auto& x : tree.files) {
    const auto& o = *k++;
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

Known read_files(sqlite3* db) {
  Known out;
  try {
    // The primary key keeps the rows in path order (SQLite's BINARY collation, as std::string's <).
    // `folder` is left empty: only a new tree's stamps are written, and it has its own.
    sql::Stmt s(db, "SELECT path, size, mtime_ns, hash, racy FROM files ORDER BY path");
    while (s.step()) out.push_back({s.text(0), {}, s.integer64(1), s.integer64(2), s.text(3), s.integer(4) != 0});
  } catch (const sql::Error&) {
    return {};  // an index of an older schema: everything is hashed
  }
  return out;
}

std::vector<std::string> edited(sqlite3* db, const std::map<std::string, std::filesystem::path>& roots,
                                const std::vector<std::string>& paths) {
  std::vector<std::string> out;
  sql::Stmt rec(db, "SELECT size, mtime_ns FROM files WHERE path = ?");
  for (const auto& rel : paths) {
    const auto slash = rel.find('/');
    const auto root = roots.find(rel.substr(0, slash));
    const auto s = root == roots.end() || slash == std::string::npos ? Stat{} : stat_of(root->second / rel.substr(slash + 1));
    rec.bind(1, rel);
    const bool same = rec.step() && s.regular && s.size == rec.integer64(0) && s.mtime_ns == rec.integer64(1);
    rec.reset();
    if (!same) out.push_back(rel);
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

namespace {

// Rows of `files` for a statement whose first columns are path, size, mtime_ns, hash, racy.
void collect(sql::Stmt& s, Known& out) {
  while (s.step()) out.push_back({s.text(0), {}, s.integer64(1), s.integer64(2), s.text(3), s.integer(4) != 0});
  s.reset();
}

// The folder rows of a tag walked whole ("calibration": the tag itself and every folder under it).
constexpr const char* kFoldersOfTag = "FROM folders WHERE path = ?1 OR (path >= ?1 || '/' AND path < ?1 || '0')";

}  // namespace

bool stamp_listed(const std::vector<Listed>& files, const std::map<std::string, std::filesystem::path>& roots, const Known& known,
                  std::int64_t build_start_ns, Tree& into) {
  const std::int64_t racy_after = build_start_ns - kRacyWindowNs;
  std::map<std::string, FolderStamp> folders;
  std::vector<FileStamp> stamped;
  for (const auto& l : files) {
    const auto s = stat_of(l.on_disk);  // through a link, as the walk's fstatat
    if (s.ok && !s.regular) return false;
    if (s.ok) {
      FileStamp f{l.path, parent_of(l.path), s.size, s.mtime_ns, {}, s.mtime_ns > racy_after};
      if (const auto* k = find(known, l.path); k && !k->racy && k->size == f.size && k->mtime_ns == f.mtime_ns) {
        f.hash = k->hash;
      } else {
        f.hash = hash_fd(::open(l.on_disk.c_str(), O_RDONLY | O_CLOEXEC));
        ++into.hashed;
      }
      stamped.push_back(std::move(f));
    }
    for (auto folder = parent_of(l.path); !folder.empty() && !folders.count(folder); folder = parent_of(folder)) {
      const auto slash = folder.find('/');
      const auto root = roots.find(folder.substr(0, slash));
      if (root == roots.end()) return false;
      const auto dir = slash == std::string::npos ? root->second : root->second / folder.substr(slash + 1);
      struct ::stat lst {};
      // The walk does not enter a link to a folder, so a file under one is not the library's.
      if (::lstat(dir.c_str(), &lst) == 0 && S_ISLNK(lst.st_mode) && slash != std::string::npos) return false;
      const auto fs = stat_of(dir);
      if (!fs.directory) return false;
      folders[folder] = {folder, fs.mtime_ns, slash == std::string::npos || fs.mtime_ns > racy_after};
    }
  }
  std::sort(stamped.begin(), stamped.end(), [](const FileStamp& a, const FileStamp& b) { return a.path < b.path; });
  stamped.erase(std::unique(stamped.begin(), stamped.end(), [](const FileStamp& a, const FileStamp& b) { return a.path == b.path; }),
                stamped.end());
  const auto before = into.files.size();
  std::move(stamped.begin(), stamped.end(), std::back_inserter(into.files));
  const auto by_path = [](const FileStamp& a, const FileStamp& b) { return a.path < b.path; };
  std::inplace_merge(into.files.begin(), into.files.begin() + static_cast<std::ptrdiff_t>(before), into.files.end(), by_path);
  for (auto& [path, f] : folders) into.folders.push_back(std::move(f));
  return true;
}

Known read_files_of(sqlite3* db, const std::vector<std::string>& paths, const std::vector<std::string>& folders) {
  Known out;
  sql::Stmt one(db, "SELECT path, size, mtime_ns, hash, racy FROM files WHERE path = ?");
  for (const auto& p : paths) {
    one.bind(1, p);
    collect(one, out);
  }
  // '0' follows '/': the range holds exactly the paths under the folder.
  sql::Stmt under(db, "SELECT path, size, mtime_ns, hash, racy FROM files WHERE path >= ?1 || '/' AND path < ?1 || '0'");
  for (const auto& f : folders) {
    under.bind(1, f);
    collect(under, out);
  }
  std::sort(out.begin(), out.end(), [](const FileStamp& a, const FileStamp& b) { return a.path < b.path; });
  out.erase(std::unique(out.begin(), out.end(), [](const FileStamp& a, const FileStamp& b) { return a.path == b.path; }), out.end());
  return out;
}

void update_part(sqlite3* db, const Tree& tree, const Known& known, const std::vector<std::string>& walked_tags) {
  sql::Stmt put(db, kPutFile);
  for (const auto& x : tree.files) {
    const auto* k = find(known, x.path);
    if (k && k->size == x.size && k->mtime_ns == x.mtime_ns && k->hash == x.hash && k->racy == x.racy) continue;
    put_file(put, x);
  }
  sql::Stmt del(db, "DELETE FROM files WHERE path = ?");
  for (const auto& k : known)
    if (!find(tree.files, k.path)) del.bind(1, k.path).run();
  sql::Stmt drop(db, std::string("DELETE ") + kFoldersOfTag);
  for (const auto& t : walked_tags) drop.bind(1, t).run();
  sql::Stmt d(db, "INSERT OR REPLACE INTO folders VALUES (?, ?, ?)");
  for (const auto& x : tree.folders) d.bind(1, x.path).bind64(2, x.mtime_ns).bind(3, x.files_checked ? 1 : 0).run();
}

bool same_part(sqlite3* db, const Tree& tree, const Known& known, const std::vector<std::string>& walked_tags) {
  if (tree.files.size() != known.size()) return false;
  auto k = known.begin();
  for (const auto& x : tree.files) {
    const auto& o = *k++;
    if (o.path != x.path || o.size != x.size || o.mtime_ns != x.mtime_ns || o.hash != x.hash || o.racy != x.racy) return false;
  }
  sql::Stmt f(db, "SELECT mtime_ns, files_checked FROM folders WHERE path = ?");
  for (const auto& x : tree.folders) {
    f.bind(1, x.path);
    const bool ok = f.step() && f.integer64(0) == x.mtime_ns && (f.integer(1) != 0) == x.files_checked;
    f.reset();
    if (!ok) return false;
  }
  sql::Stmt n(db, std::string("SELECT count(*) ") + kFoldersOfTag);
  for (const auto& t : walked_tags) {
    n.bind(1, t);
    n.step();
    const auto recorded = static_cast<std::size_t>(n.integer64(0));
    n.reset();
    const auto walked = static_cast<std::size_t>(std::count_if(tree.folders.begin(), tree.folders.end(), [&](const FolderStamp& x) {
      return x.path == t || x.path.rfind(t + "/", 0) == 0;
    }));
    if (recorded != walked) return false;
  }
  return true;
}

std::vector<std::string> entry_files_named(sqlite3* db, const std::string& name) {
  // `stem <> ''` lets SQLite use the partial index files_stem.
  sql::Stmt s(db, "SELECT path FROM files WHERE stem = ?1 AND stem <> ''");
  s.bind(1, name);
  std::vector<std::string> out;
  while (s.step()) out.push_back(s.text(0));
  return out;
}

}  // namespace sandpaper::curation::stamps
