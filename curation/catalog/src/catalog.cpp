// Compiles every entry and writes the catalog into a temporary folder, then swaps it in (catalog.hpp).
#include "sandpaper/catalog/catalog.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <map>
#include <set>
#include <unordered_set>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>
#include <ostream>
#include <random>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "sandpaper/catalog/assets.hpp"
#include "sandpaper/catalog/compare_data.hpp"
#include "sandpaper/catalog/entry_page.hpp"
#include "sandpaper/catalog/index_page.hpp"
#include "sandpaper/catalog/plot.hpp"
#include "sandpaper/catalog/render.hpp"
#include "sandpaper/curation/inputs.hpp"
#include "sandpaper/curation/percepts.hpp"
#include "sandpaper/curation/progress.hpp"
#include "sandpaper/schema/array_file.hpp"
#include "record.hpp"

namespace sandpaper::catalog {
namespace fs = std::filesystem;
namespace {

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

// A fresh folder beside `dir`, named after it, that no other run uses.
fs::path temp_beside(const fs::path& dir, const std::string& tag) {
  std::random_device rd;
  const fs::path parent = dir.parent_path().empty() ? fs::path(".") : dir.parent_path();
  for (int attempt = 0; attempt < 100; ++attempt) {
    fs::path p = parent / ("." + dir.filename().string() + "." + tag + "-" + std::to_string(::getpid()) + "-" +
                           std::to_string(rd() % 1000000));
    if (fs::create_directory(p)) return p;
  }
  throw std::runtime_error("cannot make a temporary folder beside " + dir.string());
}

// Removes the temporary folder unless the catalog was swapped in.
struct TempDir {
  fs::path path;
  ~TempDir() {
    std::error_code ec;
    if (!path.empty()) fs::remove_all(path, ec);
  }
};

void check_replaceable(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return;
  if (!fs::is_directory(dir, ec))
    throw std::invalid_argument("'" + dir.string() + "' exists and is not a folder; give a folder for the catalog");
  if (fs::is_empty(dir, ec) || fs::exists(dir / kCatalogMarker, ec)) return;
  throw std::invalid_argument("'" + dir.string() + "' is a folder that is not a catalog (no " + kCatalogMarker +
                              " in it), so it is not replaced; give a new or empty folder, or a previous catalog");
}

// True if process `pid` may still be running (a temporary it owns is not stale).
bool alive(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH); }

// Removes ".<name>.new-PID-N" and ".<name>.old-PID-N" folders beside `dir` left by runs that were
// killed (kill -9 runs no destructor); a running catalog build's folders are left alone.
void remove_stale_temporaries(const fs::path& dir) {
  std::error_code ec;
  const fs::path parent = dir.parent_path().empty() ? fs::path(".") : dir.parent_path();
  const std::string prefix = "." + dir.filename().string() + ".";
  for (const auto& e : fs::directory_iterator(parent, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string rest = name.substr(prefix.size());  // "new-1234-567890"
    if (rest.rfind("new-", 0) != 0 && rest.rfind("old-", 0) != 0) continue;
    const long pid = std::strtol(rest.c_str() + 4, nullptr, 10);
    if (!alive(pid)) fs::remove_all(e.path(), ec);
  }
}

// Puts `fresh` in place of `dir` in one step: renameat2's RENAME_EXCHANGE swaps the two names
// atomically, so a kill at any moment leaves either the old catalog or the new one at `dir`, never
// none. File systems without it (EINVAL) get the two renames, the old catalog moved aside first.
void swap_in(const fs::path& fresh, const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) {
    fs::rename(fresh, dir);
    return;
  }
  if (::renameat2(AT_FDCWD, fresh.c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) == 0) {
    fs::remove_all(fresh, ec);  // now the previous catalog
    return;
  }
  if (errno != EINVAL && errno != ENOSYS)
    throw std::runtime_error("cannot put the catalog in place of " + dir.string() + ": " + std::strerror(errno));
  const fs::path old = temp_beside(dir, "old");
  fs::remove(old);
  fs::rename(dir, old);
  try {
    fs::rename(fresh, dir);
  } catch (...) {
    fs::rename(old, dir, ec);
    throw;
  }
  fs::remove_all(old, ec);
}

// An entry's files as the record lists them, or, where the list is not one this program wrote, the
// files this program would have written for that name (none for a name that is not a plain stem).
std::vector<std::string> recorded_files(const std::string& name, const RecordedEntry& e) {
  if (auto files = e.files()) return std::move(*files);
  if (!plain_file_name(name)) return {};
  return {name + ".html", name + ".png", name + "-thumb.png", name + ".shade", compare_data_file(name)};
}

// The largest index data file an in-place update reads back: a part of 2,048 rows is about 100 KB, the
// head file about 50 bytes a part.
constexpr std::uintmax_t kMaxDataFileBytes = std::uintmax_t{256} << 20;

// At most this many entries drawn or removed for an in-place update.
constexpr std::size_t kInPlaceLimit = 256;

// The catalog's files as this version writes them: a record of another version draws everything again.
constexpr int kCatalogFormat = 3;

// How pictures are lit (render.hpp, light_azimuth_deg): a catalog drawn with another light is drawn again.
constexpr const char* kLighting = "across the ridges";

std::string settings_of(const CatalogOptions& o) {
  return nlohmann::json{{"format", kCatalogFormat}, {"lighting", kLighting}, {"picture_side", o.picture_side}, {"thumbnail_side", o.thumbnail_side},
                        {"thumbnail_window_m", o.thumbnail_window_m}, {"arrays", o.arrays}}
      .dump();
}

// Puts the previous catalog's files of one entry into the new folder: a hard link (same file
// system, no copy), else a copy. False if any is missing.
bool keep_files(const fs::path& from, const fs::path& to, const std::vector<std::string>& files) {
  for (const auto& name : files) {
    std::error_code ec;
    if (!fs::is_regular_file(from / "entries" / name, ec)) return false;
    fs::create_hard_link(from / "entries" / name, to / "entries" / name, ec);
    if (ec) fs::copy_file(from / "entries" / name, to / "entries" / name, ec);
    if (ec) return false;
  }
  return true;
}

// In one read of its size: the data file is 4.7 MB at 100,000 entries, and a character-by-character
// istreambuf_iterator copy of it took 0.1 s of a one-entry update.
std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in) return {};
  std::string text(static_cast<std::size_t>(std::max<std::streamoff>(0, in.tellg())), '\0');
  in.seekg(0);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
  return text;
}

// Writes `file` whole beside itself, then renames it over, if its text differs: a reader sees the
// old file or the new one.
void replace_if_changed(const fs::path& file, const std::string& text) {
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  if (!ec && size == text.size() && read_text(file) == text) return;
  const fs::path tmp = file.parent_path() / ("." + file.filename().string() + ".tmp-" + std::to_string(::getpid()));
  write_text(tmp, text);
  fs::rename(tmp, file);
}

// The record's hashes were read, and the rows a run then needs were not (a damaged file): thrown
// before anything the record decided was used, and answered by drawing every entry again.
struct UnreadableRecord : std::runtime_error {
  UnreadableRecord() : std::runtime_error("catalog record: a row cannot be read") {}
};

CatalogReport write_catalog_pass(const CatalogSource& source, const CatalogOptions& options, bool use_record);

}  // namespace

CatalogReport write_catalog(const compiler::Compiler& compiler, const CatalogOptions& options) {
  // An entry file the library could not read (a path that is not UTF-8, E0614) is not among its
  // entries: the catalog would leave it out unsaid. It fails the run as an entry that does not
  // compile does, and nothing is written.
  CatalogReport unread;
  for (const auto& d : compiler.library().scan_diagnostics().all())
    if (d.code == "E0614") {
      compiler::Diagnostics one;
      one.error(schema::Code::of(d.code), d.location, d.message, d.suggestion);
      unread.failures.push_back({d.location.file ? d.location.file->name : std::string("?"), compiler::format_diagnostics(one)});
    }
  if (!unread.failures.empty()) return unread;
  CatalogSource source;
  source.manifest = compiler.library().manifest();
  const auto hashes = curation::entry_input_hashes(compiler, compiler.options().calibration_dir);
  const auto& library = compiler.library();
  for (const auto& e : library.entries())
    if (library.entry(e.name) == &e) {  // a second file with a taken name is left out, as the index leaves it out
      const auto h = hashes.find(e.name);
      source.entries.emplace_back(e.name, h == hashes.end() ? std::string() : h->second);
    }
  source.compiler_for = [&](const std::vector<std::string>&) -> const compiler::Compiler& { return compiler; };
  return write_catalog(source, options);
}

CatalogReport write_catalog(const CatalogSource& source, const CatalogOptions& options) {
  try {
    return write_catalog_pass(source, options, true);
  } catch (const UnreadableRecord&) {
    // Files drawn in place so far are as the uninterrupted run would leave them, and the record was
    // not committed; the pass without it writes a new folder, with a whole record, and swaps it in.
    auto report = write_catalog_pass(source, options, false);
    report.record_unreadable = true;
    return report;
  }
}

namespace {

CatalogReport write_catalog_pass(const CatalogSource& source, const CatalogOptions& options, bool use_record) {
  if (options.output.empty()) throw std::invalid_argument("give the catalog's folder with -o DIR");
  fs::path dir = fs::absolute(options.output).lexically_normal();
  if (!dir.has_filename()) dir = dir.parent_path();  // "out/" -> "out"
  if (dir == dir.root_path()) throw std::invalid_argument("the catalog cannot replace the root folder");
  check_replaceable(dir);
  remove_stale_temporaries(dir);
  CatalogReport report;

  TempDir tmp{temp_beside(dir, "new")};
  fs::create_directories(tmp.path / "entries");
  fs::create_directories(tmp.path / "assets");

  const std::string settings = settings_of(options);
  const std::vector<std::pair<std::string, std::string>>* entries = &source.entries;
  std::vector<std::pair<std::string, std::string>> every;
  const std::string recorded_fingerprint = use_record ? recorded_index_fingerprint(dir, settings) : std::string();
  // `entries` holds only some entries (source.since): usable if the record was compared with the
  // index as it was, and if no entry among them is new (the record lacks it: a new entry rewrites
  // the whole data file, which needs every row). Otherwise every_entry() gives them all.
  bool partial = source.since && !source.since->empty() && source.entries.size() <= kInPlaceLimit &&
                 recorded_fingerprint == *source.since && fs::is_regular_file(dir / kIndexDataFile);
  std::vector<std::string> partial_names;
  if (partial)
    for (const auto& e : source.entries) partial_names.push_back(e.first);
  // What was drawn with which inputs: the hashes of the entries compared; rows and files only where needed.
  std::optional<std::unordered_map<std::string, std::string>> recorded;
  if (partial) recorded = read_record_hashes(dir, settings, &partial_names);
  if (partial && (!recorded || recorded->size() != partial_names.size())) partial = false;
  if (source.since && !partial) {
    if (!source.every_entry) throw std::logic_error("write_catalog: a partial list of entries without every_entry");
    every = source.every_entry();
    entries = &every;
  }
  if (!partial && use_record) recorded = read_record_hashes(dir, settings);
  const std::size_t entry_count = partial ? source.entry_count : entries->size();
  report.compared = entries->size();

  curation::Progress progress("catalog", entry_count, options.progress == nullptr,
                              options.progress ? *options.progress : std::cerr, options.progress_is_tty);
  const std::unordered_map<std::string, std::string> no_hashes;
  const auto& hashes = recorded ? *recorded : no_hashes;
  // Entries drawn with the same inputs and settings keep their files; the rest are drawn, by one
  // compiler that need only hold them and what they are built on.
  std::vector<bool> kept(entries->size(), false);
  std::vector<std::string> to_draw;
  std::unordered_set<std::string> present;
  present.reserve(entries->size());
  bool added = false;  // an entry the record does not have
  for (std::size_t i = 0; i < entries->size(); ++i) {
    const auto& [name, hash] = (*entries)[i];
    present.insert(name);
    const auto it = hashes.find(name);
    added = added || it == hashes.end();
    kept[i] = !hash.empty() && it != hashes.end() && it->second == hash;
    if (!kept[i]) to_draw.push_back(name);
  }
  std::vector<std::string> removed;  // partial: none (every listed entry is in the record and the index)
  if (!partial)
    for (const auto& [name, hash] : hashes)
      if (!present.count(name)) removed.push_back(name);
  std::sort(removed.begin(), removed.end());
  // Few changes: the drawn files replace theirs in the catalog itself, one rename each, rather than
  // a new folder of 3 hard links an entry swapped in (10 s at 100,000 entries); the same bound as
  // the index's in-place update.
  report.in_place = recorded && fs::is_regular_file(dir / kIndexDataFile) && to_draw.size() + removed.size() <= kInPlaceLimit;
  // In place, the rows and files of the entries drawn or removed; whole, of every entry.
  Record before;
  if (recorded) {
    std::vector<std::string> touched = to_draw;
    touched.insert(touched.end(), removed.begin(), removed.end());
    auto read = read_record(dir, settings, report.in_place ? &touched : nullptr);
    if (!read) throw UnreadableRecord();  // its hashes read and its rows do not: a damaged file
    before = std::move(*read);
  }
  if (!report.in_place)
    for (std::size_t i = 0; i < entries->size(); ++i) {
      const auto it = kept[i] ? before.find((*entries)[i].first) : before.end();
      const auto files = it == before.end() ? std::nullopt : it->second.files();
      if (kept[i] && (!files || !keep_files(dir, tmp.path, *files))) {
        kept[i] = false;
        to_draw.push_back((*entries)[i].first);
      }
    }
  const compiler::Compiler* drawing = to_draw.empty() ? nullptr : &source.compiler_for(to_draw);
  progress.set_total(to_draw.size());  // what is drawn; the kept entries cost nothing to count
  std::map<std::string, RecordedEntry> drawn;
  std::vector<IndexRow> rows;
  for (std::size_t i = 0; i < entries->size(); ++i) {
    const auto& [name, hash] = (*entries)[i];
    if (kept[i]) {
      if (!report.in_place) rows.push_back(before.at(name).row);  // in place, the data file keeps its row
      ++report.reused;
      continue;
    }
    const auto& library = drawing->library();
    const auto* entry = library.entry(name);
    if (!entry) throw std::logic_error("write_catalog: the drawing compiler's library has no entry " + name);
    const auto& e = *entry;
    auto r = drawing->compile_file(e.file);
    progress.step(e.name);
    if (!r.ok() || !r.material) {
      report.failures.push_back({e.name, compiler::format_diagnostics(r.diagnostics)});
      continue;
    }
    if (!report.failures.empty()) continue;  // nothing will be written: just find every failure
    const auto& program = *r.program;
    const Picture picture = render_picture(program, options.picture_side);
    double d[2];
    std::string axis, description;
    scan_direction(program, d, axis, description);
    const double half = picture.empty() ? half_length_inside(d, program.size_m[0], program.size_m[1])
                                        : half_length_inside(d, picture.window_m[0], picture.window_m[1]);
    const ForceScan scan = scan_force(program, half);

    EntryView view;
    view.library = &library;
    view.entry = &e;
    view.material = &*r.material;
    view.program = &program;
    view.picture = &picture;
    view.scan = &scan;
    IndexRow row;
    std::vector<std::string> files{e.name + ".html"};
    if (!picture.empty()) {
      view.picture_file = e.name + ".png";
      if (options.arrays) view.shade_file = e.name + ".shade";
      write_png(tmp.path / "entries" / view.picture_file, picture);
      // Thumbnails share one scale (options.thumbnail_window_m across), so that the index compares
      // materials' sizes and coarseness at a glance; the entry page's picture keeps the material's own.
      write_png(tmp.path / "entries" / (e.name + "-thumb.png"),
                render_picture_window(program, options.thumbnail_window_m, options.thumbnail_side));
      if (options.arrays) schema::write_shade_file(tmp.path / "entries" / view.shade_file, picture.shade);
      row.thumbnail = "entries/" + e.name + "-thumb.png";
      files.push_back(view.picture_file);
      files.push_back(e.name + "-thumb.png");
      if (options.arrays) files.push_back(view.shade_file);
    }
    row.name = e.name;
    row.family = e.family;
    row.describes = program.describes;
    row.licence = e.licence;
    row.deprecated_by = e.deprecated_by;
    row.aliases = e.aliases;
    if (program.max_lateral_force_N > 0) row.roughness = program.roughness;
    row.max_lateral_force_N = program.max_lateral_force_N;
    row.page = "entries/" + e.name + ".html";
    const auto percepts = curation::percepts_of(*r.material, program, drawing->calibration());
    row.period_m = percepts.period_m;
    row.kind = percepts.texture_kind + "|" + percepts.terms;
    for (const auto& st : e.syntax.statements)
      for (const auto& note : st.sources) row.source_kinds |= 1u << static_cast<unsigned>(note.kind);
    if (library.layered()) row.root = library.roots().at(e.root).id;
    if (source.hides) view.hides = source.hides(e.name);
    else if (const auto* hidden = library.shadowed_by(e)) view.hides = library.qualified_name(*hidden);
    view.root = row.root;
    view.weber_fraction = drawing->calibration().knowledge().force_jnd.weber_fraction;
    write_text(tmp.path / "entries" / (e.name + ".html"), entry_page_html(view));
    // The compare page's scan: through the centre of the thumbnail's square, so every entry's curve
    // covers the same span on one axis.
    const ForceScan compare_scan = scan_force(program, std::min(options.thumbnail_window_m / 2,
                                                             half_length_inside(d, program.size_m[0], program.size_m[1])),
                                           scan.speed_m_s, 801);
    const auto* fam = source.manifest.family(e.family);
    write_text(tmp.path / "entries" / compare_data_file(e.name),
               compare_data_script(row, fam ? fam->title : e.family, program.device, percepts.terms, compare_scan,
                                   options.thumbnail_window_m));
    files.push_back(compare_data_file(e.name));
    drawn[e.name] = RecordedEntry{hash, row, nlohmann::json(files).dump()};
    rows.push_back(std::move(row));
    ++report.rendered;
  }
  if (partial) report.reused += static_cast<int>(entry_count - entries->size());  // not compared: as recorded
  const std::string of_all = " of " + std::to_string(entry_count) + (entry_count == 1 ? " entry" : " entries");
  progress.finish(report.failures.empty()
                      ? "catalog: " + std::to_string(report.rendered) + of_all + " compiled and drawn"
                      : "catalog: " + std::to_string(report.failures.size()) + of_all +
                            (report.failures.size() == 1 ? " does not compile" : " do not compile"));
  if (!report.failures.empty()) return report;

  const std::string marker = "Written by `sandpaper library catalog`; the folder is replaced whole by the next run, or its "
                             "changed entries' files one by one.\nlibrary " + source.manifest.name + " " + source.manifest.version + "\n";
  if (report.in_place) {
    // Each drawn file is renamed over its old one, each page after its pictures; then the index
    // page and its data; then what is gone is removed; the record is committed last, so a run
    // killed before that draws these entries again (docs/CATALOG.md, "Incremental builds").
    std::optional<RecordWriter> opened;
    if (!drawn.empty() || !removed.empty() || recorded_fingerprint != source.index_fingerprint) {
      opened.emplace(dir / kRecordFile, settings);
      opened->set_index_fingerprint(source.index_fingerprint);
    }
    std::set<std::string> stale;
    for (const auto& [name, e] : drawn) {
      const auto files = e.files().value();  // written by this run
      for (const auto& f : files)
        if (f != name + ".html") fs::rename(tmp.path / "entries" / f, dir / "entries" / f);
      fs::rename(tmp.path / "entries" / (name + ".html"), dir / "entries" / (name + ".html"));
      // A recorded list that is not one this program wrote is not trusted (recorded_files).
      if (const auto it = before.find(name); it != before.end())
        for (const auto& f : recorded_files(name, it->second))
          if (std::find(files.begin(), files.end(), f) == files.end()) stale.insert(f);
      if (!e.hash.empty()) opened->put(name, e);
      else opened->erase(name);
    }
    for (const auto& name : removed) {
      if (const auto it = before.find(name); it != before.end())
        for (const auto& f : recorded_files(name, it->second)) stale.insert(f);
      opened->erase(name);
    }
    // The drawn entries' rows put in the data file at their places (an entry added or removed, a
    // family gained or lost, or a data file that is not one: the whole file, from every row of the
    // record). Written only where they differ: with nothing changed, nothing is written.
    {
      std::optional<IndexFiles> patched;
      // A file far larger than any this program writes (a part of 2,048 rows is about 100 KB) is not read into memory.
      const ReadIndexFile read_index_file = [&](const std::string& relative) -> std::optional<std::string> {
        std::error_code size_ec;
        const auto size = fs::file_size(dir / relative, size_ec);
        if (size_ec || size > kMaxDataFileBytes) return std::nullopt;
        return read_text(dir / relative);
      };
      if (!added && removed.empty()) patched = patch_index(read_index_file, source.manifest, rows);
      const bool whole = !patched;
      if (whole) {
        auto read = read_record(dir, settings);
        if (!read) throw UnreadableRecord();  // an index without the rows it could not read
        auto& all = *read;
        // Partial, the record holds every entry (none came or went), in the index's order by name.
        std::vector<std::string> names;
        if (partial) {
          for (const auto& [name, e] : all) names.push_back(name);
          std::sort(names.begin(), names.end());
        } else {
          for (const auto& [name, hash] : *entries) names.push_back(name);
        }
        std::vector<IndexRow> all_rows;
        for (const auto& name : names)
          if (const auto d = drawn.find(name); d != drawn.end()) all_rows.push_back(d->second.row);
          else if (const auto a = all.find(name); a != all.end()) all_rows.push_back(std::move(a->second.row));
        patched = index_files(source.manifest, all_rows);
      }
      // The parts first, then the head that names them, then the page that loads them.
      fs::create_directories(dir / kIndexPartsFolder);
      for (const auto& [relative, text] : *patched)
        if (relative != kIndexDataFile && relative != "index.html") replace_if_changed(dir / relative, text);
      replace_if_changed(dir / kIndexDataFile, patched->at(kIndexDataFile));
      replace_if_changed(dir / "index.html", patched->at("index.html"));
      // Written whole with fewer entries: the parts past the last are no one's.
      if (whole)
        for (std::size_t k = patched->size() - 2;; ++k) {
          std::error_code gone;
          if (!fs::remove(dir / index_part_file(k), gone)) break;
        }
    }
    for (const auto& a : assets()) replace_if_changed(dir / "assets" / std::string(a.name), std::string(a.text));
    replace_if_changed(dir / kCatalogMarker, marker);
    std::error_code ec;
    for (const auto& f : stale) fs::remove(dir / "entries" / f, ec);
    if (opened) opened->commit();
    report.entries = static_cast<int>(entry_count);
    return report;
  }
  fs::create_directories(tmp.path / kIndexPartsFolder);
  for (const auto& [relative, text] : index_files(source.manifest, rows)) write_text(tmp.path / relative, text);
  {
    RecordWriter record(tmp.path / kRecordFile, settings);
    record.set_index_fingerprint(source.index_fingerprint);
    for (std::size_t i = 0; i < entries->size(); ++i) {
      const auto& [name, hash] = (*entries)[i];
      if (kept[i]) record.put(name, before.at(name));
      else if (const auto it = drawn.find(name); it != drawn.end() && !hash.empty()) record.put(name, it->second);
    }
    record.commit();
  }
  for (const auto& a : assets()) write_text(tmp.path / "assets" / std::string(a.name), std::string(a.text));
  write_text(tmp.path / kCatalogMarker, marker);
  // A catalog written by an earlier version kept its record as inputs.json; it goes with the old folder.
  swap_in(tmp.path, dir);
  tmp.path.clear();
  report.entries = static_cast<int>(rows.size());
  return report;
}

}  // namespace

}  // namespace sandpaper::catalog
