// The in-place update of an index (docs/LIBRARY.md, "Incremental builds"): when a few entries
// changed, only their files are parsed, only they and what is built on them are compiled, and
// their rows are replaced in one SQLite transaction in the index itself. Reading and copying
// every entry's file, and the whole index, is what made a one-entry update at 100,000 entries
// take 10 s. Anything this path cannot decide cheaply and exactly (a name taken twice, a parse or
// compile error, calibration or library.toml changed, many entries) is left to the batched build.
#include "index_update.hpp"

#include <algorithm>
#include <deque>
#include <set>

#include "sandpaper/compiler/display_paths.hpp"
#include "entry_inputs.hpp"
#include "index_write.hpp"
#include "reach.hpp"
#include "stamps.hpp"

namespace sandpaper::curation {

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::vector<std::string> column(sqlite3* db, const char* query, const std::string& arg) {
  sql::Stmt s(db, query);
  s.bind(1, arg);
  std::vector<std::string> out;
  while (s.step()) out.push_back(s.text(0));
  return out;
}

}  // namespace

std::vector<stamps::Listed> tag_changed(const std::vector<std::filesystem::path>& changed, const std::filesystem::path& lib_dir,
                                        const std::filesystem::path& cal_dir, std::string& error) {
  const auto under = [](const std::filesystem::path& file, const std::filesystem::path& dir) -> std::optional<std::filesystem::path> {
    const auto rel = file.lexically_relative(dir);
    if (rel.empty() || *rel.begin() == "..") return std::nullopt;
    return rel;
  };
  const std::pair<const char*, std::filesystem::path> roots[] = {
      {"library", std::filesystem::absolute(lib_dir).lexically_normal()},
      {"calibration", std::filesystem::absolute(cal_dir).lexically_normal()}};
  std::vector<stamps::Listed> out;
  for (const auto& p : changed) {
    const auto abs = std::filesystem::absolute(p).lexically_normal();
    std::optional<std::pair<std::string, std::filesystem::path>> found;
    for (const auto& [tag, dir] : roots)
      if (auto rel = under(abs, dir); rel && !found) found = {{tag, *rel}};
    // Through links (a library folder named by a link, a path given by its real name).
    std::error_code ec;
    for (const auto& [tag, dir] : roots)
      if (!found)
        if (auto rel = under(std::filesystem::weakly_canonical(abs, ec), std::filesystem::weakly_canonical(dir, ec))) found = {{tag, *rel}};
    if (!found) {
      error = "the changed file " + p.string() + " is in neither the library folder " + roots[0].second.string() +
              " nor the calibration folder " + roots[1].second.string() + "; list only files of this library";
      return {};
    }
    const auto& [tag, rel] = *found;
    // Hidden files and folders are not the library's (the index's own .index/, editors' swap files).
    if (std::any_of(rel.begin(), rel.end(), [](const auto& part) { return part.string().rfind('.', 0) == 0 && part != "."; })) continue;
    out.push_back({rel == "." ? std::string(tag) : std::string(tag) + "/" + rel.generic_string(), abs});
  }
  return out;
}

std::optional<IndexBuildResult> update_in_place(const IndexOptions& options, const std::filesystem::path& lib_dir,
                                                const std::filesystem::path& cal_dir, const std::filesystem::path& index_path,
                                                std::int64_t start_ns, Progress& progress) {
  const auto lib_abs = std::filesystem::absolute(lib_dir).lexically_normal().string();
  sqlite3* db = nullptr;
  try {
    db = open_rw(index_path);  // rolls back what a killed update left in its journal
  } catch (const sql::Error&) {
    return std::nullopt;
  }
  Closer closer{db};
  sqlite3_busy_timeout(db, 10'000);
  const auto meta = [&](const std::string& key) {
    const auto v = column(db, "SELECT value FROM meta WHERE key = ?", key);
    return v.empty() ? std::string() : v.front();
  };
  try {
    if (meta("schema_version") != std::to_string(kIndexSchemaVersion) || meta("library_dir") != lib_abs ||
        meta("device") != options.device || !meta("below").empty())  // a root of a layered path: index.cpp
      return std::nullopt;
  } catch (const sql::Error&) {
    return std::nullopt;  // not an index
  }
  const auto previous_fingerprint = meta("fingerprint");

  // Every file's stamp, hashing only files whose stamp changed; or, told which files changed, their
  // stamps alone (and the calibration's, a few files): then nothing here grows with the library.
  const bool listed = options.changed.has_value();
  stamps::Tree tree;
  stamps::Known known;
  std::set<std::string> stamped_now;  // listed: the paths stamped now (the rest keep their rows)
  if (listed) {
    std::string error;
    auto files = tag_changed(*options.changed, lib_dir, cal_dir, error);
    if (!error.empty()) return std::nullopt;  // build_index reports it
    files.push_back({"library/library.toml", lib_dir / "library.toml"});
    std::vector<std::string> paths;
    for (const auto& f : files) {
      paths.push_back(f.path);
      stamped_now.insert(f.path);
    }
    known = stamps::read_files_of(db, paths, {"calibration"});
    if (!stamps::stamp_listed(files, {{"library", lib_dir}, {"calibration", cal_dir}}, known, start_ns, tree)) return std::nullopt;
  } else {
    known = stamps::read_files(db);
    stamps::walk(lib_dir, "library", known, start_ns, false, tree);
  }
  stamps::walk(cal_dir, "calibration", known, start_ns, true, tree);
  const auto hash_of = [&](const std::string& path) -> std::string {
    if (const auto* f = stamps::find(tree.files, path)) return f->hash;
    if (!listed || stamped_now.count(path) || path.rfind("calibration/", 0) == 0) return "absent";
    const auto recorded = column(db, "SELECT hash FROM files WHERE path = ?", path);
    return recorded.empty() ? std::string("absent") : recorded.front();
  };
  std::map<std::string, std::string> global_files;
  for (const auto& f : tree.files)
    if (f.path.rfind("calibration/", 0) == 0 || f.path == "library/library.toml") global_files[f.path] = f.hash;
  const auto global = global_inputs(global_files, options.device);
  if (stamps::fnv_hex(global) != meta("global_inputs")) return std::nullopt;  // every entry is redone

  IndexBuildResult r;
  r.path = index_path;
  r.in_place = true;
  r.files_hashed = tree.hashed;
  r.previous_fingerprint = previous_fingerprint;
  const auto entry_count = [&] {
    sql::Stmt n(db, "SELECT count(*) FROM entries");
    n.step();
    return static_cast<std::size_t>(n.integer64(0));
  };
  if (listed ? stamps::same_part(db, tree, known, {"calibration"}) : stamps::same(db, tree, known)) {  // nothing to write
    r.ok = true;
    r.in_place = false;
    r.entries = r.reused = entry_count();
    r.rewritten.emplace();
    return r;
  }

  // Files whose content changed, came or went.
  std::set<std::string> changed_entry_files, changed_other;
  for (const auto& f : tree.files)
    if (const auto* k = stamps::find(known, f.path); !k || k->hash != f.hash)
      (ends_with(f.path, ".hmat") && f.path.rfind("library/", 0) == 0 ? changed_entry_files : changed_other).insert(f.path);
  for (const auto& k : known)
    if (!stamps::find(tree.files, k.path))
      (ends_with(k.path, ".hmat") && k.path.rfind("library/", 0) == 0 ? changed_entry_files : changed_other).insert(k.path);
  const std::size_t limit = std::max<std::size_t>(options.batch, 1);
  if (changed_entry_files.size() > limit) return std::nullopt;

  // The changed entry files as they were (their rows) and as they are (parsed now).
  std::set<std::string> old_names, touched;  // touched: names and aliases whose meaning may change
  std::vector<std::string> present;
  for (const auto& path : changed_entry_files) {
    const auto rel = path.substr(8);  // "library/"
    for (const auto& n : column(db, "SELECT name FROM entries WHERE file = ?", rel)) {
      old_names.insert(n);
      touched.insert(n);
      for (const auto& a : column(db, "SELECT alias FROM aliases WHERE name = ?", n)) touched.insert(a);
    }
    if (hash_of(path) != "absent") present.push_back(rel);
  }
  const compiler::Library fresh(lib_dir, present);
  if (fresh.scan_diagnostics().has_errors()) return std::nullopt;
  for (const auto& e : fresh.entries()) {
    if (!e.parsed_ok || fresh.entry(e.name) != &e) return std::nullopt;
    touched.insert(e.name);
    touched.insert(e.aliases.begin(), e.aliases.end());
  }
  // A name or alias another file also has: which one wins is decided over the whole library.
  for (const auto& n : touched)
    for (const auto& file : column(db,
                                   "SELECT file FROM entries WHERE name = ?1 UNION "
                                   "SELECT e.file FROM aliases a JOIN entries e ON e.name = a.name WHERE a.alias = ?1",
                                   n))
      if (!changed_entry_files.count("library/" + file)) return std::nullopt;
  // A second file with a name (left out of the index): the batched build decides which one counts.
  // An unchanged file has its recorded row, so the stamps' index on names finds it.
  for (const auto& n : touched)
    for (const auto& path : stamps::entry_files_named(db, n))
      if (!changed_entry_files.count(path)) return std::nullopt;
  // What is built on them, backwards through `depends`: entries that read a changed file, or are
  // built on a touched name, then on those entries, and so on.
  std::set<std::string> affected;
  for (const auto& e : fresh.entries()) affected.insert(e.name);
  std::deque<std::string> names(touched.begin(), touched.end());
  const auto add = [&](const std::string& n) {
    if (old_names.count(n) && !fresh.entry(n)) return;  // its file is gone
    if (!affected.insert(n).second) return;
    names.push_back(n);
    for (const auto& a : column(db, "SELECT alias FROM aliases WHERE name = ?", n)) names.push_back(a);
  };
  for (const auto& path : changed_other)
    for (const auto& n : column(db, "SELECT name FROM depends WHERE target = ? AND kind = 'file'", path)) add(n);
  while (!names.empty() && affected.size() <= limit) {
    const auto t = names.front();
    names.pop_front();
    for (const auto& n : column(db, "SELECT name FROM depends WHERE target = ? AND kind = 'entry'", t)) add(n);
  }
  if (affected.size() > limit) return std::nullopt;

  // The part of the library they need: their files, and down their `like` chains and the
  // reference entry, each name resolved as the whole library resolves it.
  std::vector<std::string> roots(affected.begin(), affected.end());
  if (!fresh.manifest().reference.empty()) roots.push_back(fresh.manifest().reference);
  const auto files = files_reached(
      db, roots, {},
      [&](const std::string& n) -> std::optional<ReachedEntry> {
        if (const auto* e = fresh.entry(n)) return ReachedEntry{e->relative_path, e->likes};
        return std::nullopt;
      },
      [&](const std::string& file) { return changed_entry_files.count("library/" + file) > 0; });
  const compiler::Compiler c(compiler::CompileOptions{options.device, lib_dir, cal_dir, {}},
                             compiler::Library(lib_dir, std::vector<std::string>(files.begin(), files.end())));
  const auto& lib = c.library();
  const auto inputs = entry_inputs(lib, hash_of, global);
  // Every entry read but not redone must hash as its row says: if not, a dependency was missed,
  // and the batched build, which hashes everything, decides.
  for (const auto& [name, in] : inputs)
    if (!affected.count(name)) {
      const auto had = column(db, "SELECT hash FROM inputs WHERE name = ?", name);
      if (had.empty() || had.front() != in.hash) return std::nullopt;
    }

  std::vector<Compiled> compiled;
  const compiler::DisplayPaths disp(lib_dir);
  progress.set_total(affected.size());
  for (const auto& name : affected) {
    const auto* e = lib.entry(name);
    if (!e || !inputs.count(name)) return std::nullopt;
    auto res = c.compile_file(disp.path_of(e->relative_path));
    if (!res.ok()) return std::nullopt;  // the batched build reports it, with every other error
    compiled.push_back({e, std::move(*res.material), std::move(*res.program)});
  }

  const auto fingerprint = listed ? stamps::fingerprint_update(meta("fingerprint"), known, tree.files) : stamps::fingerprint(tree.files);
  // One transaction, in the index itself: a kill before COMMIT leaves a journal that the next
  // opener rolls back, so readers see the old index or the new one.
  sql::exec(db, "PRAGMA synchronous = FULL; BEGIN IMMEDIATE");
  try {
    for (const auto& n : old_names) delete_entry(db, n);
    for (const auto& n : affected) delete_entry(db, n);
    EntryWriter writer(db, lib, c.calibration(), disp);
    for (const auto& x : compiled) {
      writer.insert(x, inputs.at(x.entry->name));
      progress.step(x.entry->name);
    }
    if (listed)
      stamps::update_part(db, tree, known, {"calibration"});
    else
      stamps::update(db, tree, known);
    write_families_and_meta(db, lib, index_meta(c, lib_abs, cal_dir, options.device, fingerprint, stamps::fnv_hex(global)));
    sql::exec(db, "COMMIT");
  } catch (...) {
    sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
  r.ok = true;
  r.compiled = compiled.size();
  r.entries = entry_count();
  r.reused = r.entries - r.compiled;
  std::set<std::string> rewritten = old_names;
  rewritten.insert(affected.begin(), affected.end());
  r.rewritten.emplace(rewritten.begin(), rewritten.end());
  return r;
}

}  // namespace sandpaper::curation
