#pragma once
// The library's SQLite index (`sandpaper library index`; schema in docs/LIBRARY.md): entries,
// aliases, perceptual coordinates, a physical summary, provenance with the `source` notes, and an
// FTS5 table for words, an R*Tree on the perceptual coordinates, and what each entry was built
// from. Built incrementally (only entries whose inputs changed are compiled again) and atomically:
// a temp file beside the index, renamed over it only when every entry compiled; any failure
// leaves the previous index byte-identical; a build killed part-way is resumed by the next one.
#include <filesystem>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/library.hpp"
#include "sandpaper/curation/progress.hpp"
#include "sandpaper/curation/weber_fractions.hpp"
#include "sandpaper/curation/word_rank.hpp"

struct sqlite3;

namespace sandpaper::curation {

// 7: an entry file whose path is not UTF-8 is no longer read (E0614, F30); an index of 6 may list
// one, so it is built again. 8: an image texture's period_m is its spatial scale (percepts.hpp).
inline constexpr int kIndexSchemaVersion = 9;

// $SANDPAPER_LIBRARY_INDEX, else <library_dir>/.index/library.sqlite.
std::filesystem::path default_index_path(const std::filesystem::path& library_dir);

// In a layered path every root has its own index, <root>/.index/library.sqlite ($SANDPAPER_LIBRARY_INDEX
// names one file, so it is not used there).
std::filesystem::path layer_index_path(const std::filesystem::path& root_dir);

// The index's `fingerprint`: a hash over every file of the library folder (relative path and
// FNV-1a 64 of its bytes; hidden files and folders such as .index/ left out) and of the calibration
// folder, which sets the roughness (a sum of one hash per file: stamps.hpp). It detects edits, not tampering.
std::string library_fingerprint(const std::filesystem::path& library_dir, const std::filesystem::path& calibration_dir);

struct IndexOptions {
  std::filesystem::path library_dir;       // empty: compiler::default_library_dir()
  std::filesystem::path calibration_dir;   // empty: calibration::default_calibration_dir()
  std::filesystem::path index_path;        // empty: default_index_path(library_dir)
  std::string device = "sim";              // coordinates are compiled on this device
  bool full = false;                       // compile every entry; reuse nothing from a previous build
  std::size_t batch = 256;                 // entries per transaction: a killed build keeps its whole batches
  // The roots below this one in a layered path (front first). Then the index holds this root's
  // entries only, compiled over the whole path, and records each lower root's index fingerprint:
  // their indexes (layer_index_path) must be fresh, and a change below redoes this root's entries.
  std::vector<std::filesystem::path> below = {};
  // The files that changed since the index was built, as an editor's save hook, a file watcher or
  // `git diff --name-only` knows (paths on disk, in the library or calibration folder; hidden ones
  // are ignored): the update stats these and the calibration alone, without walking the library,
  // and takes every other file's recorded stamp as it is. A build without them still finds what
  // the list left out. When the change needs more than an in-place update, the whole build runs.
  // Not with `below`, nor with `full`.
  std::optional<std::vector<std::filesystem::path>> changed = std::nullopt;
};

struct IndexBuildResult {
  bool ok = false;
  compiler::Diagnostics diagnostics;  // why it failed (entries that do not compile, ...), relocated for display
  std::string error;                  // an I/O or SQLite failure, in words
  std::size_t entries = 0;             // entries in the index
  std::size_t compiled = 0, reused = 0;  // of them: compiled now, rows kept from the previous build
  std::size_t files_hashed = 0;        // files read to hash them (the others' stamps had not changed)
  bool resumed = false;                // started from the rows of a build that was killed
  bool in_place = false;               // few entries or stamps changed: updated in the index itself, in one transaction
  // After an update in place, or none needed: the entries whose rows it rewrote or removed, and the
  // index's fingerprint before it; every other row is as it was then. nullopt after a batched build,
  // which may have rewritten any row (write_catalog_from_index compares only these when it can).
  std::optional<std::vector<std::string>> rewritten;
  std::string previous_fingerprint;
  std::filesystem::path path;
  bool part_of_path = false;           // a layered root compiled over only what its entries reach of the roots below
};

// Compiles on `device` every entry whose inputs (its text, images, `like` chain, the calibration,
// library.toml, the compiler version) changed since the previous index, and writes the index.
// Throws calibration::CalibrationError for unreadable calibration; everything else is reported in the result.
IndexBuildResult build_index(const IndexOptions& options, Progress& progress);

// One row of `entries`, with its aliases and coordinates.
struct IndexedEntry {
  std::string name, family, family_title, describes, licence, deprecated_by, file, library_version;
  std::vector<std::string> aliases, likes;
  double roughness = 0, max_lateral_force_N = 0, period_m = 0;
  std::string texture_kind, period_class, character, terms, physical;
  std::vector<std::pair<std::string, double>> others;  // other percepts
  std::vector<std::pair<std::string, double>> term_params;  // Percepts::term_params
  std::string root;  // in a layered path, the id of the root it is from (curation/layers.hpp); else ""
};

struct IndexedStatement {
  int line = 0;
  std::string keyword, text;
  std::vector<std::pair<std::string, std::string>> sources;  // (kind, text)
};

struct IndexedProvenance {
  std::string parameter;   // "texture.period"
  double value_si = 0;
  std::string si_unit, stated, layer, source;
  std::vector<std::pair<std::string, std::string>> notes;  // the stating statement's `source` notes (kind, text)
};

// A read-only open index. Throws IndexError if the file cannot be opened or is not an index of this schema.
struct IndexError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
class Index {
 public:
  explicit Index(const std::filesystem::path& path);
  // Takes an open database that holds an index of this schema (an in-memory one: LayeredIndex's
  // view over a path); throws IndexError, closing it, if it does not.
  explicit Index(sqlite3* db);
  ~Index();
  Index(const Index&) = delete;
  Index& operator=(const Index&) = delete;

  std::string meta(const std::string& key) const;  // "" if absent
  // The force JND's Weber fraction the index was compiled with (dimensionless, e.g. 0.125; Minsky
  // 1995 5.4.2), from `meta`. Throws IndexError (damaged, F43) unless a number in (0, 1].
  double weber_fraction() const;
  // Every dimension's fraction (weber_fractions.hpp), from `meta`; throws IndexError (damaged) unless each is
  // a number in (0, 1].
  WeberFractions weber_fractions() const;
  std::vector<IndexedEntry> entries() const;       // sorted by name
  std::optional<IndexedEntry> entry(const std::string& name) const;
  // Entries by their row ids in `entries` (the ids of `search` and `coordinates` too).
  std::vector<IndexedEntry> entries_by_rowid(const std::vector<std::int64_t>& rowids) const;
  // For comparing many entries (near), without aliases and other percepts: the textured entries in
  // a box of ln(maximum lateral force / 1 N), log2(period / 1 m) (a texture without a period spans
  // the whole axis) and texture class (one number per texture kind and program terms); the
  // untextured ones.
  struct Box {
    double ln_force_lo = -1e30, ln_force_hi = 1e30, log2_period_lo = -1e30, log2_period_hi = 1e30;
    double class_lo = -1e30, class_hi = 1e30;
    std::optional<bool> periodless;  // only textures without a period (true), with one (false), or both
  };
  std::vector<IndexedEntry> textured_in_box(const Box& box) const;
  double texture_class(const std::string& name) const;  // -1 for an untextured entry
  // The class of texture kind and program terms "kind|terms" in this index; -2 if no entry has it.
  double class_of(const std::string& kind_terms) const;
  std::vector<IndexedEntry> untextured() const;
  // Untextured entries in a box of law coordinates (weber_fractions.hpp's law_coordinates, JNDs; a dimension
  // an entry lacks spans its whole axis) and class (program terms).
  struct LawBox {
    std::array<double, 3> lo{-1e30, -1e30, -1e30}, hi{1e30, 1e30, 1e30};
    double class_lo = -1e30, class_hi = 1e30;
  };
  std::vector<IndexedEntry> untextured_in_box(const LawBox& box) const;
  std::size_t size() const;  // entries
  // The entry's name for a name or alias; nullopt if neither.
  std::optional<std::string> resolve(const std::string& name_or_alias) const;
  std::vector<std::string> names_and_aliases() const;
  std::vector<std::string> families() const;
  // The families that are published stimulus sets (library.toml `stimulus-set = true`): the thesis'.
  std::vector<std::string> stimulus_families() const;
  std::vector<IndexedStatement> statements(const std::string& name) const;
  std::vector<IndexedProvenance> provenance(const std::string& name) const;
  // FTS5 match (Porter stems) over name, aliases, describes and the family's id, title and describes;
  // not the `source` notes, whose citations name other materials: (name, bm25 rank; lower is better).
  std::vector<std::pair<std::string, double>> full_text(const std::string& fts_query) const;
  // The entries each of whose `words` (lower-case) is in the text of its name, aliases, describes or
  // family as a substring, with those fields, by name: the candidates word_score() ranks (a word
  // beginning one of a field's words is in it). Aliases and family title as word_rank.hpp's WordFields.
  std::vector<WordFields> word_candidates(const std::vector<std::string>& words) const;
  // Every entry's input hash (table `inputs`), by name: what `library catalog` compares with the
  // hashes its pages were drawn from.
  std::vector<std::pair<std::string, std::string>> input_hashes() const;
  std::optional<std::string> input_hash(const std::string& name) const;  // nullopt: no such entry
  // The entry files (relative to the library) that compiling `names` reads: theirs, those of
  // every entry they are built on (recursively) and of the reference entry, and those of the
  // entries their `deprecated replaced-by` names. A compiler over compiler::Library(dir, these)
  // compiles them as over the whole library.
  std::vector<std::string> files_reached(const std::vector<std::string>& names) const;
  sqlite3* handle() const { return db_; }

 private:
  sqlite3* db_ = nullptr;
};

// The files on disk that compiling `names` read (each entry's file, its images and those of the
// entries it is built on, as the `depends` table records them) whose size or modification time is
// not what `index` recorded, or that are gone: an edit in place that index_state's cheap check
// does not see. `library_dir` is the index's library folder.
std::vector<std::filesystem::path> edited_inputs(const Index& index, const std::filesystem::path& library_dir,
                                                 const std::vector<std::string>& names);

enum class IndexState { Missing, Stale, Fresh };
// Missing (no file), stale (another schema or library folder, or the stamps differ), fresh. The
// check reads no file: it compares the modification times of the library's folders, and the
// stamps of the files of the root, the calibration and recently changed folders (docs/LIBRARY.md,
// "When the index is stale"); an edit in place elsewhere is seen by the next `library index`.
IndexState index_state(const std::filesystem::path& index_path, const std::filesystem::path& library_dir,
                       const std::filesystem::path& calibration_dir);
// The same for one root of a layered path with `below` under it: also stale when it was built over
// other roots, when a lower root's index is not fresh, or when one changed since (its fingerprint).
IndexState index_state(const std::filesystem::path& index_path, const std::filesystem::path& library_dir,
                       const std::filesystem::path& calibration_dir, const std::vector<std::filesystem::path>& below);

}  // namespace sandpaper::curation
