#include "cmd_library.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/schema/json_text.hpp"
#include "sandpaper/schema/patch_json.hpp"
#include "sandpaper/curation/check.hpp"
#include "sandpaper/curation/display.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/layers.hpp"
#include "sandpaper/curation/review.hpp"
#include "sandpaper/curation/near.hpp"
#include "sandpaper/curation/search.hpp"

namespace sandpaper::cli {

namespace {

namespace cur = sandpaper::curation;

// "1 entry", "2 entries".
std::string entries_text(std::size_t n) { return std::to_string(n) + (n == 1 ? " entry" : " entries"); }

std::string num(double v, int digits = 3) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

std::string pad(const std::string& s, std::size_t w) { return s.size() >= w ? s : s + std::string(w - s.size(), ' '); }

void add_paths(CLI::App* sub, LibraryCommandOptions& o, bool index) {
  sub->add_option("--library", o.library_dir, "library folder, or folders front first as LAB:WORLD (default: $SANDPAPER_LIBRARY_PATH, $SANDPAPER_LIBRARY, $SANDPAPER_DATA_DIR/library, or the shipped library)");
  sub->add_option("--calibration", o.calibration_dir, "calibration folder (default: $SANDPAPER_CALIBRATION, $SANDPAPER_DATA_DIR/calibration, or the shipped calibration)");
  if (index)
    sub->add_option("--index", o.index, "SQLite index file (default: $SANDPAPER_LIBRARY_INDEX or <library>/.index/library.sqlite)");
}

struct Paths {
  std::filesystem::path library, calibration, index;  // library: the front root; index: its index
  std::vector<std::filesystem::path> roots;           // the library path, front first (one folder unless layered)
  std::vector<std::filesystem::path> indexes;         // each root's index, parallel to roots
  bool layered() const { return roots.size() > 1; }
  std::vector<std::filesystem::path> below(std::size_t i) const {
    return {roots.begin() + static_cast<std::ptrdiff_t>(i) + 1, roots.end()};
  }
};

Paths paths_of(const CommonOptions& common, const LibraryCommandOptions& o) {
  Paths p;
  p.library = !o.library_dir.empty() ? o.library_dir : !common.library_dir.empty() ? common.library_dir : compiler::default_library_dir().string();
  p.calibration = !o.calibration_dir.empty()       ? std::filesystem::path(o.calibration_dir)
                  : !common.calibration_dir.empty() ? std::filesystem::path(common.calibration_dir)
                                                    : calibration::default_calibration_dir();
  p.roots = o.library_dir.empty() && common.library_dir.empty() ? compiler::default_library_path()
                                                                 : compiler::split_library_path(p.library.string());
  if (p.roots.empty()) throw std::invalid_argument("--library is empty (give --library DIR, or LAB:WORLD for a layered library)");
  for (const auto& r : p.roots)
    if (!std::filesystem::is_directory(r))
      throw std::invalid_argument("no library folder at " + r.string() + " (give --library DIR, or LAB:WORLD for a layered library)");
  p.library = p.roots.front();
  if (p.layered() && !o.index.empty())
    throw std::invalid_argument("--index names one file; a layered library path keeps an index in each root "
                                "(<root>/.index/library.sqlite): leave --index out");
  p.index = o.index.empty() ? (p.layered() ? cur::layer_index_path(p.library) : cur::default_index_path(p.library))
                            : std::filesystem::path(o.index);
  if (p.layered())
    for (const auto& r : p.roots) p.indexes.push_back(cur::layer_index_path(r));
  else
    p.indexes = {p.index};
  return p;
}

int print_build_failure(const cur::IndexBuildResult& r, const char* who) {
  std::cerr << compiler::format_diagnostics(r.diagnostics);
  if (!r.error.empty()) {
    std::cerr << "sandpaper " << who << ": index not written: " << r.error << "\n";
    return kExitUsage;
  }
  std::size_t errors = 0;
  for (const auto& d : r.diagnostics.all()) errors += d.severity == compiler::Severity::Error;
  std::cerr << "sandpaper " << who << ": index not written: " << errors << " error(s) in the library (`sandpaper library check` "
            << "says more); " << r.path.string() << " is unchanged\n";
  return kExitBadInput;
}

// Whether the index at `index` can be read and was built from this library folder (over these roots).
bool previous_index_answers(const std::filesystem::path& index, const std::filesystem::path& root, const std::string& below) {
  try {
    const cur::Index idx(index);
    return idx.meta("library_dir") == std::filesystem::absolute(root).lexically_normal().string() && idx.meta("below") == below;
  } catch (const cur::IndexError&) {
    return false;
  }
}

std::string below_text(const std::vector<std::filesystem::path>& below) {
  std::string out;
  for (const auto& b : below) out += std::filesystem::absolute(b).lexically_normal().string() + "\n";
  return out;
}

// Builds each root's index that is missing or stale, the bottom root first (a root's index is
// built over those below it); returns the exit code of a failed build, or 0 (also when a rebuild
// failed but the previous index of that root can still answer).
int ensure_index(const Paths& p, bool quiet, const char* who) {
  for (std::size_t i = p.roots.size(); i-- > 0;) {
    const auto below = p.below(i);
    const auto state = cur::index_state(p.indexes[i], p.roots[i], p.calibration, below);
    if (state == cur::IndexState::Fresh) continue;
    std::cerr << "sandpaper " << who << ": the index " << p.indexes[i].string() << " is "
              << (state == cur::IndexState::Missing ? "missing" : "stale (the library or calibration changed)")
              << "; building it\n";
    auto progress = cur::Progress::on_stderr("indexing", 0, quiet);
    cur::IndexOptions io{p.roots[i], p.calibration, p.indexes[i], "sim"};
    io.below = below;
    const auto r = cur::build_index(io, progress);
    if (!r.ok) {
      const int rc = print_build_failure(r, who);
      // A library mid-edit should not stop curators searching it: the last good index still answers,
      // marked as such, as long as it is an index of this library in this schema.
      if (state == cur::IndexState::Stale && previous_index_answers(p.indexes[i], p.roots[i], below_text(below))) {
        std::cerr << "sandpaper " << who << ": answering from the previous index, built before the library changed; "
                  << "fix the errors above and it is rebuilt\n";
        continue;
      }
      return rc;
    }
    progress.finish("indexed " + entries_text(r.entries) + " into " + r.path.string());
  }
  return kExitOk;
}

nlohmann::json entry_json(const cur::IndexedEntry& e, bool layered) {
  nlohmann::json others = nlohmann::json::object();
  for (const auto& [k, v] : e.others) others[k] = v;
  nlohmann::json j = {{"name", e.name},
          {"aliases", e.aliases},
          {"family", e.family},
          {"describes", e.describes},
          {"licence", e.licence},
          {"deprecated_by", e.deprecated_by.empty() ? nlohmann::json(nullptr) : nlohmann::json(e.deprecated_by)},
          {"file", e.file},
          {"library_version", e.library_version},
          {"likes", e.likes},
          {"compiled_roughness", e.roughness},
          {"compiled_max_lateral_force_N", e.max_lateral_force_N},
          {"texture_kind", e.texture_kind},
          {"period_m", e.period_m},
          {"period_class", e.period_class},
          {"character", e.character},
          {"terms", e.terms},
          {"other_percepts", others},
          {"physical", e.physical}};
  if (layered) j["root"] = e.root;  // the id of the root it is from: `like ROOT:NAME` names it
  return j;
}

// The files of `entries` ((root, name)) saved in place since their root's index was built, by root:
// an edit the cheap staleness check (index_state) does not see, in a folder whose time it keeps.
std::map<std::size_t, std::vector<std::filesystem::path>> edited_since_index(
    const Paths& p, const cur::LayeredIndex& layers, const std::vector<std::pair<std::size_t, std::string>>& entries) {
  std::map<std::size_t, std::vector<std::string>> by_root;
  for (const auto& [layer, name] : entries) by_root[layer].push_back(name);
  std::map<std::size_t, std::vector<std::filesystem::path>> out;
  for (const auto& [layer, names] : by_root)
    if (auto files = cur::edited_inputs(layers.index(layer), p.roots[layer], names); !files.empty())
      out[layer] = std::move(files);
  return out;
}

// Brings the indexes up to date after those edits, saying so: the root's index from the files
// alone (the bottom root) or built again (a root in front, small), then the roots in front of it.
// Queries then answer with what the files say now, not with the old values.
int refresh_edited(const Paths& p, const std::map<std::size_t, std::vector<std::filesystem::path>>& edited, bool quiet,
                   const char* who) {
  for (const auto& [layer, files] : edited) {
    std::cerr << "sandpaper " << who << ": " << files.size() << " file" << (files.size() == 1 ? "" : "s") << " of "
              << p.roots[layer].string() << " changed since its index was built (" << files.front().string()
              << (files.size() > 1 ? ", ..." : "") << "); updating the index\n";
    auto progress = cur::Progress::on_stderr("indexing", 0, quiet);
    cur::IndexOptions io{p.roots[layer], p.calibration, p.indexes[layer], "sim"};
    io.below = p.below(layer);
    if (io.below.empty()) io.changed = files;
    const auto r = cur::build_index(io, progress);
    if (!r.ok) return print_build_failure(r, who);
    progress.finish("indexed " + entries_text(r.entries));
  }
  return ensure_index(p, quiet, who);  // the roots in front of an updated one
}

// Over a layered path, the entries of lower roots that the roots in front change are compiled over
// the path, as explain compiles them; one that does not compile there is answered from its root's
// index, with the compiler's errors on stderr.
void see_through(cur::LayeredIndex& idx, const Paths& p, const char* who) {
  if (!p.layered()) return;
  const auto failed = idx.see_through_path(p.calibration, "sim");
  if (failed.all().empty()) return;
  std::cerr << compiler::format_diagnostics(failed) << "sandpaper " << who
            << ": the entries above do not compile over this library path; their own root's index answers for them\n";
}

// "world:corduroy" for an entry of a layered path, else its name.
std::string shown_name(const cur::IndexedEntry& e, bool layered) { return layered ? e.root + ":" + e.name : e.name; }

int unknown_entry(const cur::LayeredIndex& idx, const std::string& name, const char* who) {
  const auto guess = compiler::closest_match(name, idx.names_and_aliases());
  std::cerr << "sandpaper " << who << ": no library entry or alias named '" << name << "'; "
            << (guess.empty() ? "`sandpaper library search WORDS` finds entries by words" : "did you mean '" + guess + "'?") << "\n";
  return kExitBadInput;
}

int run_check(const Paths& p, const LibraryCommandOptions& o) {
  const compiler::Library scan(p.roots);
  std::size_t total = 0;
  for (std::size_t i = 0; i < scan.roots().size(); ++i)
    if (o.root.empty() || scan.roots()[i].id == o.root)
      for (const auto& e : scan.entries()) total += e.root == i;
  auto progress = cur::Progress::on_stderr("checking", total, o.quiet);
  cur::CheckOptions co{p.library, p.calibration, o.devices, p.roots, o.root};
  const auto r = cur::check_library(co, progress);
  const bool failed = r.errors() > 0 || (o.werror && r.warnings() > 0);
  if (o.json) {
    std::cout << schema::json_text(nlohmann::json{{"ok", !failed},
                                                  {"entries", r.entries},
                                                  {"devices", r.devices},
                                                  {"errors", r.errors()},
                                                  {"warnings", r.warnings()},
                                                  {"uncalibrated_devices", r.uncalibrated},
                                                  {"accepted", diagnostics_json(r.accepted)},
                                                  {"diagnostics", diagnostics_json(r.diagnostics)}},
                                   2)
              << "\n";
  } else {
    std::cerr << compiler::format_diagnostics(r.diagnostics);
  }
  progress.finish(r.summary() + (o.werror && r.warnings() > 0 && r.errors() == 0 ? " (--werror: warnings fail)" : ""));
  return failed ? kExitBadInput : kExitOk;
}

int run_review(const Paths& p, const LibraryCommandOptions& o) {
  if (p.layered()) {
    std::cerr << "sandpaper library review: review one library root (--library ROOT): a pull request changes one repository\n";
    return kExitUsage;
  }
  auto progress = cur::Progress::on_stderr("checking", 0, o.quiet);
  const auto r = cur::review_library({p.library, p.calibration, o.devices, o.base}, progress);
  if (!r.error.empty()) {
    std::cerr << "sandpaper library review: " << r.error << "\n";
    return kExitBadInput;
  }
  const auto summary = std::to_string(r.changed_files.size()) + " changed file" + (r.changed_files.size() == 1 ? "" : "s") + ", " +
                       std::to_string(r.entries.size()) + (r.entries.size() == 1 ? " entry" : " entries") + " touched, checked on " +
                       std::to_string(r.devices) + " devices: " + std::to_string(r.failing.all().size()) + " to fix, " +
                       std::to_string(r.accepted.all().size()) + " accepted, " + std::to_string(r.old_warnings) +
                       " warnings the base had already";
  if (o.json) {
    std::cout << schema::json_text(nlohmann::json{{"ok", r.ok()},
                                                  {"base", o.base},
                                                  {"changed_files", r.changed_files},
                                                  {"entries", r.entries},
                                                  {"failing", diagnostics_json(r.failing)},
                                                  {"accepted", diagnostics_json(r.accepted)},
                                                  {"old_warnings", r.old_warnings},
                                                  {"by_hand", r.by_hand}},
                                   2)
              << "\n";
  } else {
    std::cerr << compiler::format_diagnostics(r.failing);
    std::cout << "review of " << p.library.string() << " against " << o.base << ": " << summary << "\n";
    if (!r.by_hand.empty()) {
      std::cout << "for a person to look at:\n";
      for (const auto& line : r.by_hand) std::cout << "  - " << line << "\n";
    }
    std::cout << (r.ok() ? "review passed\n" : "review FAILED: fix what is above, or accept a warning the entry means (accept CODE \"reason\")\n");
  }
  progress.finish("");
  return r.ok() ? kExitOk : kExitBadInput;
}

int run_index(const Paths& p, const LibraryCommandOptions& o) {
  if (!o.changed.empty() && p.layered()) {
    std::cerr << "sandpaper library index: --changed updates one library root; with a layered path, run it with "
                 "--library ROOT for the root that changed, then without --changed for the roots above it\n";
    return kExitUsage;
  }
  nlohmann::json roots = nlohmann::json::array();
  // The bottom root first: a root's index is built over the indexes of the roots below it.
  for (std::size_t i = p.roots.size(); i-- > 0;) {
    auto progress = cur::Progress::on_stderr("indexing", 0, o.quiet);
    cur::IndexOptions io{p.roots[i], p.calibration, p.indexes[i], "sim", o.full};
    io.below = p.below(i);
    if (!o.changed.empty()) io.changed = changed_files(o.changed);
    const auto r = cur::build_index(io, progress);
    if (!r.ok) return print_build_failure(r, "library index");
    progress.finish("indexed " + entries_text(r.entries));
    const cur::Index built(r.path);
    const nlohmann::json j{{"ok", true},         {"entries", r.entries},           {"compiled", r.compiled},
                           {"reused", r.reused}, {"files_hashed", r.files_hashed}, {"resumed", r.resumed}, {"in_place", r.in_place},
                           {"index", r.path.string()}, {"root", cur::root_id(built, p.roots[i])}};
    roots.insert(roots.begin(), j);
    if (!o.json)
      std::cout << "indexed " << entries_text(r.entries) << " of " << built.meta("library_name") << " " << built.meta("library_version")
                << (p.layered() ? " (root " + cur::root_id(built, p.roots[i]) + ")" : std::string()) << " into " << r.path.string() << " ("
                << r.compiled << " compiled, " << r.reused << " unchanged" << (r.resumed ? ", resumed from an interrupted build" : "")
                << (r.in_place ? ", updated in place" : "") << ")\n";
  }
  // One root: its object, as before layering; several: every root's, front first.
  if (o.json)
    std::cout << schema::json_text(p.layered() ? nlohmann::json{{"ok", true}, {"roots", roots}} : roots.front(), 2)
              << "\n";
  return kExitOk;
}

int run_search(const Paths& p, const LibraryCommandOptions& o) {
  cur::SearchQuery q;
  q.words = o.words;
  q.family = o.family;
  q.limit = o.limit;
  if (!o.roughness.empty()) q.roughness = cur::parse_roughness_range(o.roughness);  // invalid_argument: exit 2
  if (const int rc = ensure_index(p, o.quiet, "library search")) return rc;
  auto hits = [&] {
    cur::LayeredIndex idx(p.roots, p.indexes);
    see_through(idx, p, "library search");
    return idx.search(q);
  }();
  // The hits' own files edited in place since the index was built: the index brought up to date
  // from them, and the search asked again (only then).
  std::map<std::size_t, std::vector<std::filesystem::path>> edited;
  {
    const cur::LayeredIndex layers(p.roots, p.indexes);
    std::vector<std::pair<std::size_t, std::string>> found;
    for (const auto& h : hits)
      for (std::size_t i = 0; i < layers.size(); ++i)
        if (!p.layered() || layers.id(i) == h.entry.root) found.emplace_back(i, h.entry.name);
    edited = edited_since_index(p, layers, found);
  }
  if (!edited.empty()) {
    if (const int rc = refresh_edited(p, edited, o.quiet, "library search")) return rc;
    cur::LayeredIndex idx(p.roots, p.indexes);
    see_through(idx, p, "library search");
    hits = idx.search(q);
  }
  if (o.json) {
    auto arr = nlohmann::json::array();
    for (const auto& h : hits) {
      auto j = entry_json(h.entry, p.layered());
      j["matched"] = h.why;
      j["matched_alias"] = h.matched_alias.empty() ? nlohmann::json(nullptr) : nlohmann::json(h.matched_alias);
      arr.push_back(j);
    }
    std::cout << schema::json_text(arr, 2) << "\n";
  } else {
    std::size_t wn = 0, wf = 0;
    for (const auto& h : hits)
      wn = std::max(wn, shown_name(h.entry, p.layered()).size()), wf = std::max(wf, h.entry.family.size());
    for (const auto& h : hits) {
      std::cout << pad(shown_name(h.entry, p.layered()), wn) << "  " << pad(h.entry.family, wf) << "  ";
      if (h.entry.max_lateral_force_N > 0)
        std::cout << "roughness " << pad(schema::roughness_text(h.entry.roughness), 5);
      else
        std::cout << "untextured     ";  // as wide as "roughness 0.123"
      std::cout << "  \"" << h.entry.describes << "\"";
      if (!h.matched_alias.empty()) std::cout << "  (alias " << h.matched_alias << ")";
      if (!h.entry.deprecated_by.empty()) std::cout << "  [deprecated: use " << h.entry.deprecated_by << "]";
      std::cout << "\n";
    }
  }
  if (hits.empty()) {
    std::cerr << "no entries match\n";
    return kExitBadInput;  // like grep: 1 = nothing found
  }
  return kExitOk;
}

int run_show(const Paths& p, const LibraryCommandOptions& o) {
  if (const int rc = ensure_index(p, o.quiet, "library show")) return rc;
  std::map<std::size_t, std::vector<std::filesystem::path>> edited;
  {
    cur::LayeredIndex first(p.roots, p.indexes);
    if (const auto at = first.resolve(o.name)) edited = edited_since_index(p, first, {*at});
  }
  if (!edited.empty())
    if (const int rc = refresh_edited(p, edited, o.quiet, "library show")) return rc;
  cur::LayeredIndex layers(p.roots, p.indexes);
  see_through(layers, p, "library show");
  const auto found = layers.resolve(o.name);
  if (!found) return unknown_entry(layers, o.name, "library show");
  const auto& [layer, name] = *found;
  const auto& idx = layers.index_of(layer, name);
  const auto e = *layers.entry(layer, name);
  const auto statements = idx.statements(name);
  const auto prov = idx.provenance(name);
  const cur::DisplayPaths shown(p.roots[layer]);
  if (o.json) {
    auto j = entry_json(e, p.layered());
    j["family_title"] = e.family_title;
    j["statements"] = nlohmann::json::array();
    for (const auto& s : statements) {
      nlohmann::json src = nlohmann::json::array();
      for (const auto& [k, t] : s.sources) src.push_back({{"kind", k}, {"text", t}});
      j["statements"].push_back({{"line", s.line}, {"keyword", s.keyword}, {"text", s.text}, {"sources", src}});
    }
    j["provenance"] = nlohmann::json::array();
    for (const auto& r : prov) {
      nlohmann::json notes = nlohmann::json::array();
      for (const auto& [k, t] : r.notes) notes.push_back({{"kind", k}, {"text", t}});
      j["provenance"].push_back({{"parameter", r.parameter}, {"value_si", r.value_si}, {"si_unit", r.si_unit}, {"stated", r.stated},
                                 {"layer", r.layer}, {"source", r.source}, {"source_notes", notes}});
    }
    j["compiled_on"] = idx.meta("device");
    std::cout << schema::json_text(j, 2) << "\n";
    return kExitOk;
  }
  std::cout << shown_name(e, p.layered());
  if (!e.aliases.empty()) {
    std::string a;
    for (const auto& x : e.aliases) a += (a.empty() ? "" : ", ") + x;
    std::cout << "  (alias " << a << ")";
  }
  std::cout << "\n  describes  \"" << e.describes << "\"\n"
            << "  family     " << e.family << (e.family_title.empty() ? "" : " (" + e.family_title + ")") << "\n"
            << "  licence    " << e.licence << "\n"
            << "  file       " << shown.path_of(e.file) << " (library " << e.library_version << ")\n";
  if (p.layered()) {
    std::cout << "  root       " << e.root << " (" << layer + 1 << " of " << p.roots.size() << " in the library path)";
    for (std::size_t i = layer + 1; i < layers.size(); ++i)
      if (layers.index(i).resolve(e.name) == e.name) std::cout << "; hides " << layers.id(i) << ":" << e.name;
    std::cout << "\n";
  }
  if (!e.deprecated_by.empty()) std::cout << "  DEPRECATED replaced by " << e.deprecated_by << "\n";
  if (!e.likes.empty()) {
    std::string l;
    for (const auto& x : e.likes) l += (l.empty() ? "" : ", ") + x;
    std::cout << "  like       " << l << "\n";
  }
  std::cout << "perceptual coordinates (compiled on device " << idx.meta("device") << ")\n";
  if (e.max_lateral_force_N > 0) {
    std::cout << "  roughness              " << schema::roughness_text(e.roughness) << " (ratio scale, " << idx.meta("roughness_map") << ")\n"
              << "  maximum lateral force  " << num(e.max_lateral_force_N) << " N\n"
              << "  texture                " << e.texture_kind;
    if (e.period_m > 0) std::cout << ", period " << num(e.period_m * 1000) << " mm";
    if (!e.period_class.empty()) std::cout << ", period class " << e.period_class << " (Minsky 1995 6.3.6)";
    if (!e.character.empty()) std::cout << ", group " << e.character << " (6.3.7)";
    std::cout << "\n";
  } else {
    std::cout << "  no texture: roughness 0 (the roughness map does not apply)\n";
  }
  for (const auto& [k, v] : e.others) std::cout << "  " << pad(k, 23) << num(v) << " (ratio scale)\n";
  std::cout << "physical\n  " << e.physical << "\n  terms: " << (e.terms.empty() ? "none" : e.terms) << "\n";
  std::cout << "statements (" << shown.path_of(e.file) << ")\n";
  for (const auto& s : statements) {
    std::cout << "  " << std::setw(3) << s.line << "  " << s.text << "\n";
    for (const auto& [k, t] : s.sources) std::cout << "         source " << k << " \"" << t << "\"\n";
  }
  std::cout << "resolution (every parameter: value in SI, layer, where it was said)\n";
  // Sources in any root of the path, shown as explain and check show them.
  std::vector<std::pair<std::string, std::filesystem::path>> ids;
  for (std::size_t i = 0; i < p.roots.size(); ++i) ids.emplace_back(layers.id(i), p.roots[i]);
  const cur::DisplayPaths every_root(ids);
  std::size_t wp = 0;
  for (const auto& r : prov) wp = std::max(wp, r.parameter.size());
  for (const auto& r : prov) {
    // As explain shows them (95 mm, 0 deg), not in raw SI: the JSON keeps value_si and si_unit.
    const std::string value = r.si_unit.empty() ? r.stated : schema::display_value(r.value_si, r.si_unit);
    std::cout << "  " << pad(r.parameter, wp) << "  " << pad(value, 12) << "  " << pad(r.layer, 10) << "  "
              << every_root.in_text(r.source) << "\n";
    for (const auto& [k, t] : r.notes) std::cout << "      source " << k << " \"" << t << "\"\n";
  }
  return kExitOk;
}

// "a, b, c".
std::string listed(const std::vector<std::string>& words) {
  std::string s;
  for (const auto& w : words) s += (s.empty() ? "" : ", ") + w;
  return s;
}

int run_near(const Paths& p, const LibraryCommandOptions& o) {
  if (const int rc = ensure_index(p, o.quiet, "library near")) return rc;
  std::map<std::size_t, std::vector<std::filesystem::path>> edited;
  {
    cur::LayeredIndex first(p.roots, p.indexes);
    if (const auto at = first.resolve(o.name)) edited = edited_since_index(p, first, {*at});
  }
  if (!edited.empty())
    if (const int rc = refresh_edited(p, edited, o.quiet, "library near")) return rc;
  cur::LayeredIndex layers(p.roots, p.indexes);
  see_through(layers, p, "library near");
  const auto found = layers.resolve(o.name);
  if (!found) return unknown_entry(layers, o.name, "library near");
  const auto& [layer, name] = *found;
  const auto& idx = layers.index_of(layer, name);
  if (!o.family.empty()) {  // a family no root has is a typo, not an empty answer
    std::vector<std::string> fams;
    for (std::size_t i = 0; i < layers.size(); ++i)
      for (auto& f : layers.index(i).families()) fams.push_back(std::move(f));
    if (std::find(fams.begin(), fams.end(), o.family) == fams.end()) {
      const auto guess = compiler::closest_match(o.family, fams);
      throw std::invalid_argument("no family '" + o.family + "' in the library; " +
                                  (guess.empty() ? "families: " + listed(fams) : "did you mean '" + guess + "'?"));
    }
  }
  const auto ns = layers.nearest(layer, name, o.limit, o.family);
  const std::string from = p.layered() ? layers.id(layer) + ":" + name : name;
  if (o.json) {
    auto arr = nlohmann::json::array();
    for (const auto& n : ns) {
      nlohmann::json j{{"name", n.entry.name}, {"family", n.entry.family}, {"compiled_roughness", n.entry.roughness},
                       {"distance_jnd", n.distance}, {"force_jnd", n.force_steps}, {"period_doublings", n.period_doublings},
                       {"why", n.why}};
      if (p.layered()) j["root"] = n.entry.root;
      arr.push_back(j);
    }
    std::cout << schema::json_text(
                     nlohmann::json{
                         {"from", from}, {"weber_fraction", idx.weber_fraction()}, {"nearest", arr}},
                     2)
              << "\n";
    return kExitOk;
  }
  std::cout << "nearest to " << from << " (distance in force JND steps of " << num(idx.weber_fraction() * 100)
            << " %; a period doubling counts " << num(cur::kJndPerPeriodDoubling) << ", docs/LIBRARY.md)\n";
  std::size_t wn = 0;
  for (const auto& n : ns) wn = std::max(wn, shown_name(n.entry, p.layered()).size());
  for (const auto& n : ns)
    std::cout << "  " << std::setw(6) << std::fixed << std::setprecision(1) << n.distance << std::defaultfloat << "  "
              << pad(shown_name(n.entry, p.layered()), wn) << "  " << n.why << "\n";
  return kExitOk;
}

}  // namespace

// The files of `--changed`, with "-" replaced by the lines of stdin (cli.hpp).
std::vector<std::filesystem::path> changed_files(const std::vector<std::string>& listed) {
  std::vector<std::filesystem::path> out;
  for (const auto& f : listed) {
    if (f != "-") {
      out.emplace_back(f);
      continue;
    }
    for (std::string line; std::getline(std::cin, line);) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (!line.empty()) out.emplace_back(line);
    }
  }
  return out;
}


void add_library_commands(CLI::App& library, LibraryCommandOptions& o) {
  o.check = library.add_subcommand("check", "validate every entry: metadata, sources, names, cycles, compiles on every device, JND collisions");
  add_paths(o.check, o, false);
  o.check->add_option("--device", o.devices, "check only these devices (default: every device of the calibration)");
  o.check->add_flag("--json", o.json, "print one JSON object with the diagnostics");
  o.check->add_flag("--quiet", o.quiet, "no progress on stderr");
  o.check->add_flag("--werror", o.werror, "warnings fail the check too");
  o.check->add_option("--root", o.root, "in a layered library (--library LAB:WORLD), check only the root with this id");

  o.review = library.add_subcommand("review",
                                    "review a change to a library in git: check what changed since --base (and what is built on it) on "
                                    "every device; fail on errors and on new warnings not accepted; list what a person must look at");
  add_paths(o.review, o, false);
  o.review->add_option("--base", o.base, "the commit to compare with: a branch, tag or hash (for a pull request, its target branch)")
      ->capture_default_str();
  o.review->add_option("--device", o.devices, "review on these devices only (default: every device of the calibration)");
  o.review->add_flag("--json", o.json, "print one JSON object");
  o.review->add_flag("--quiet", o.quiet, "no progress on stderr");

  o.index_cmd = library.add_subcommand("index", "build the SQLite index (atomically; a failed build leaves the old one)");
  add_paths(o.index_cmd, o, true);
  o.index_cmd->add_flag("--json", o.json, "print JSON");
  o.index_cmd->add_flag("--full", o.full, "compile every entry again (by default only entries whose inputs changed)");
  o.index_cmd->add_flag("--quiet", o.quiet, "no progress on stderr");
  o.index_cmd
      ->add_option("--changed", o.changed,
                   "only these files changed (a save hook, a watcher, `git diff --name-only`; - reads them from stdin, one a line): "
                   "update the index from them without looking at the rest of the library")
      ->expected(1, -1)
      ->excludes("--full");

  o.search = library.add_subcommand("search", "find entries by name, alias, words and roughness range (exit 1 if none match)");
  o.search->add_option("words", o.words, "words to look for in names, aliases, descriptions and families; rough/smooth keep the rougher/smoother half, roughest/smoothest first");
  o.search->add_option("--roughness", o.roughness, "ratio-scale range: A..B, A.. or ..B");
  o.search->add_option("--family", o.family, "only this family");
  o.search->add_option("--limit", o.limit, "at most this many entries")->capture_default_str();
  add_paths(o.search, o, true);
  o.search->add_flag("--json", o.json, "print JSON");
  o.search->add_flag("--quiet", o.quiet, "no progress if the index has to be built");

  o.show = library.add_subcommand("show", "print an entry: metadata, statements with their sources, resolution");
  o.show->add_option("name", o.name, "entry name or alias")->required();
  add_paths(o.show, o, true);
  o.show->add_flag("--json", o.json, "print JSON");
  o.show->add_flag("--quiet", o.quiet, "no progress if the index has to be built");

  o.near = library.add_subcommand("near", "the perceptually nearest entries, with the distance in force JNDs and why");
  o.near->add_option("name", o.name, "entry name or alias")->required();
  o.near->add_option("--limit", o.limit, "at most this many entries")->capture_default_str();
  o.near->add_option("--family", o.family, "only entries of this family");
  add_paths(o.near, o, true);
  o.near->add_flag("--json", o.json, "print JSON");
  o.near->add_flag("--quiet", o.quiet, "no progress if the index has to be built");
}

int cmd_library_sub(const CommonOptions& common, LibraryCommandOptions o) {
  const bool any = o.check->parsed() || o.index_cmd->parsed() || o.search->parsed() || o.show->parsed() || o.near->parsed() ||
                   o.review->parsed();
  if (!any) return -1;
  o.json = o.json || common.json;
  try {
    const auto p = paths_of(common, o);
    if (o.check->parsed()) return run_check(p, o);
    if (o.index_cmd->parsed()) return run_index(p, o);
    if (o.search->parsed()) return run_search(p, o);
    if (o.show->parsed()) return run_show(p, o);
    if (o.review->parsed()) return run_review(p, o);
    return run_near(p, o);
  } catch (const cur::IndexError& e) {
    std::cerr << "sandpaper library: " << e.what() << "\n";
    return kExitUsage;
  }
}

}  // namespace sandpaper::cli
