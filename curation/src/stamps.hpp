#pragma once
// File and folder stamps for incremental index builds and for the cheap staleness check of
// queries (docs/LIBRARY.md, "Incremental builds"; internal to sandpaper_curation).
//
// A stamp is (size, modification time in ns). A build hashes only files whose stamp changed since
// the last build. A stamp taken within kRacyWindowNs of the build is "racy": the file system's
// clock is coarse (a jiffy, or 2 s on FAT), so an edit made just after the stamp could keep it;
// racy files are always re-hashed and racy folders always listed (the "racy git" problem).
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

struct sqlite3;

namespace sandpaper::curation::stamps {

inline constexpr std::int64_t kRacyWindowNs = 2'000'000'000;

struct FileStamp {
  std::string path;    // "library/textiles/corduroy.hmat", "calibration/maps/roughness.toml"
  std::string folder;  // "library/textiles"
  std::int64_t size = 0, mtime_ns = 0;
  std::string hash;    // FNV-1a 64 of the bytes, 16 hex digits
  bool racy = false;
};

struct FolderStamp {
  std::string path;        // "library", "library/textiles"
  std::int64_t mtime_ns = 0;
  bool files_checked = false;  // queries stat every file of it (roots, calibration, racy folders)
};

// Stamps as an index recorded them, sorted by path (read_files; `folder` not read).
using Known = std::vector<FileStamp>;
// The stamp of `path` in `known`, or nullptr.
const FileStamp* find(const Known& known, const std::string& path);

struct Tree {
  std::vector<FolderStamp> folders;
  std::vector<FileStamp> files;  // sorted by path
  std::size_t hashed = 0;        // files read and hashed (the rest reused a known hash)
};

std::int64_t now_ns();

// Walks `dir` (hidden files and folders left out) under the tag "library" or "calibration". A
// file whose stamp equals a non-racy stamp in `known` keeps its hash; the others are read and hashed.
// `every_file_checked`: queries will stat every file of every folder (the calibration: a few files).
void walk(const std::filesystem::path& dir, const std::string& tag, const Known& known,
          std::int64_t build_start_ns, bool every_file_checked, Tree& into);

// Hex FNV-1a 64 of a string (for entry input hashes).
std::string fnv_hex(const std::string& bytes);

// The index's `fingerprint` of the stamps of every file: FNV-1a 64 of the schema's name plus the
// sum (mod 2^64) of each "path hash" line's FNV-1a 64. A sum, so that an update told which files
// changed can take their old lines out and put their new ones in (fingerprint_update) without
// the other files. It detects edits, not tampering.
std::string fingerprint(const std::vector<FileStamp>& files);
// `old` (a fingerprint) with the lines of `removed` taken out and those of `added` put in.
std::string fingerprint_update(const std::string& old, const std::vector<FileStamp>& removed, const std::vector<FileStamp>& added);

// A file named by the caller as changed (`library index --changed`): its tagged path
// ("library/textiles/corduroy.hmat") and where it is on disk.
struct Listed {
  std::string path;
  std::filesystem::path on_disk;
};
// The stamps of the listed files alone, without walking: a file that is gone is left out; each
// one's folders, up to its root, are stamped too (a file added or removed changes its folder's
// time, which queries check). `known` holds at least their recorded stamps. False when only a
// walk can tell: a listed path is a folder or not a regular file, or one of its folders is gone.
bool stamp_listed(const std::vector<Listed>& files, const std::map<std::string, std::filesystem::path>& roots, const Known& known,
                  std::int64_t build_start_ns, Tree& into);

// Creates (if absent) and fills the `files` and `folders` tables of an open index.
void write(sqlite3* db, const Tree& tree);
// Brings the `files` and `folders` tables up to `tree`, writing only the file rows that differ
// from `known` (the tables as read by read_files): what an in-place update writes.
void update(sqlite3* db, const Tree& tree, const Known& known);
// Whether `tree` has exactly the stamps, hashes and folders the index records.
bool same(sqlite3* db, const Tree& tree, const Known& known);
// The `files` table of an index, sorted by path; empty if it has none.
Known read_files(sqlite3* db);

// For a tree of some files only (stamp_listed, plus walks of small folders) and `known`, the
// recorded stamps of exactly those paths (read_files_of): update() and same() for those rows and
// the tree's folders alone; every other row is kept as it is.
// `walked_tags`: roots walked whole ("calibration"), whose folder rows are replaced, not merged.
void update_part(sqlite3* db, const Tree& tree, const Known& known, const std::vector<std::string>& walked_tags);
bool same_part(sqlite3* db, const Tree& tree, const Known& known, const std::vector<std::string>& walked_tags);
// The recorded stamps of `paths` and of every path under one of `folders` ("calibration"),
// sorted by path.
Known read_files_of(sqlite3* db, const std::vector<std::string>& paths, const std::vector<std::string>& folders);
// Of the tagged `paths` ("library/textiles/corduroy.hmat"), those whose file on disk (found
// through `roots`, tag -> folder) is gone or has another size or modification time than recorded,
// or that have no record.
std::vector<std::string> edited(sqlite3* db, const std::map<std::string, std::filesystem::path>& roots,
                                const std::vector<std::string>& paths);
// The recorded paths of entry files ("library/.../NAME.hmat") whose name is `name`.
std::vector<std::string> entry_files_named(sqlite3* db, const std::string& name);

// The cheap check: every recorded folder still has its modification time and no folder was added
// or removed under it; in folders marked files_checked, every file keeps its stamp (and racy files
// their hash). `roots` maps a tag to its folder. False at the first difference.
bool unchanged(sqlite3* db, const std::map<std::string, std::filesystem::path>& roots);

}  // namespace sandpaper::curation::stamps
