#include "cmd_library.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/schema/patch_json.hpp"
#include "sandpaper/curation/check.hpp"
#include "sandpaper/curation/display.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/near.hpp"
#include "sandpaper/curation/search.hpp"

namespace sandpaper::cli {

namespace {

namespace cur = sandpaper::curation;

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
  std::filesystem::path library, calibration, index;  // library: the front root
  std::vector<std::filesystem::path> roots;           // the library path, front first (one folder unless layered)
};

// The index holds one library folder; a layered path is checked, and compiled by every command, but not indexed yet.
void one_root(const Paths& p, const char* who) {
  if (p.roots.size() > 1)
    throw std::invalid_argument(std::string("sandpaper ") + who +
                                " works on one library folder; index each root of the path on its own "
                                "(--library DIR); `library check` and every compile take the layered path");
}

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
  p.index = o.index.empty() ? cur::default_index_path(p.library) : std::filesystem::path(o.index);
  return p;
}

int print_build_failure(const cur::IndexBuildResult& r, const char* who) {
  std::cerr << compiler::format_diagnostics(r.diagnostics);
  if (!r.error.empty()) {
    std::cerr << "sandpaper " << who << ": cannot write the index: " << r.error << "\n";
    return kExitUsage;
  }
  std::size_t errors = 0;
  for (const auto& d : r.diagnostics.all()) errors += d.severity == compiler::Severity::Error;
  std::cerr << "sandpaper " << who << ": index not written: " << errors << " error(s) in the library (`sandpaper library check` "
            << "says more); " << r.path.string() << " is unchanged\n";
  return kExitBadInput;
}

// Whether the index at p.index can be read and was built from this library folder.
bool previous_index_answers(const Paths& p) {
  try {
    const cur::Index idx(p.index);
    return idx.meta("library_dir") == std::filesystem::absolute(p.library).lexically_normal().string();
  } catch (const cur::IndexError&) {
    return false;
  }
}

// Builds the index when it is missing or stale; returns the exit code of a failed build, or 0
// (also when the rebuild failed but the previous index of this library can still answer).
int ensure_index(const Paths& p, bool quiet, const char* who) {
  const auto state = cur::index_state(p.index, p.library, p.calibration);
  if (state == cur::IndexState::Fresh) return kExitOk;
  std::cerr << "sandpaper " << who << ": the index " << p.index.string() << " is "
            << (state == cur::IndexState::Missing ? "missing" : "stale (the library or calibration changed)")
            << "; building it\n";
  auto progress = cur::Progress::on_stderr("indexing", 0, quiet);
  const auto r = cur::build_index({p.library, p.calibration, p.index, "sim"}, progress);
  if (!r.ok) {
    const int rc = print_build_failure(r, who);
    // A library mid-edit should not stop curators searching it: the last good index still answers,
    // marked as such, as long as it is an index of this library in this schema.
    if (state == cur::IndexState::Stale && previous_index_answers(p)) {
      std::cerr << "sandpaper " << who << ": answering from the previous index, built before the library changed; "
                << "fix the errors above and it is rebuilt\n";
      return kExitOk;
    }
    return rc;
  }
  progress.finish("indexed " + std::to_string(r.entries) + " entries into " + r.path.string());
  return kExitOk;
}

nlohmann::json entry_json(const cur::IndexedEntry& e) {
  nlohmann::json others = nlohmann::json::object();
  for (const auto& [k, v] : e.others) others[k] = v;
  return {{"name", e.name},
          {"aliases", e.aliases},
          {"family", e.family},
          {"describes", e.describes},
          {"licence", e.licence},
          {"deprecated_by", e.deprecated_by.empty() ? nlohmann::json(nullptr) : nlohmann::json(e.deprecated_by)},
          {"file", e.file},
          {"library_version", e.library_version},
          {"likes", e.likes},
          {"roughness", e.roughness},
          {"max_lateral_force_N", e.max_lateral_force_N},
          {"texture_kind", e.texture_kind},
          {"period_m", e.period_m},
          {"period_class", e.period_class},
          {"character", e.character},
          {"terms", e.terms},
          {"other_percepts", others},
          {"physical", e.physical}};
}

int unknown_entry(const cur::Index& idx, const std::string& name, const char* who) {
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
    std::cout << nlohmann::json{{"ok", !failed},
                                {"entries", r.entries},
                                {"devices", r.devices},
                                {"errors", r.errors()},
                                {"warnings", r.warnings()},
                                {"diagnostics", diagnostics_json(r.diagnostics)}}
                     .dump(2)
              << "\n";
  } else {
    std::cerr << compiler::format_diagnostics(r.diagnostics);
  }
  progress.finish(r.summary() + (o.werror && r.warnings() > 0 && r.errors() == 0 ? " (--werror: warnings fail)" : ""));
  return failed ? kExitBadInput : kExitOk;
}

int run_index(const Paths& p, const LibraryCommandOptions& o) {
  auto progress = cur::Progress::on_stderr("indexing", 0, o.quiet);
  const auto r = cur::build_index({p.library, p.calibration, p.index, "sim", o.full}, progress);
  if (!r.ok) return print_build_failure(r, "library index");
  progress.finish("indexed " + std::to_string(r.entries) + " entries");
  if (o.json)
    std::cout << nlohmann::json{{"ok", true},         {"entries", r.entries},           {"compiled", r.compiled},
                                {"reused", r.reused}, {"files_hashed", r.files_hashed}, {"resumed", r.resumed}, {"in_place", r.in_place},
                                {"index", r.path.string()}}
                     .dump(2)
              << "\n";
  else
    std::cout << "indexed " << r.entries << " entries of " << cur::Index(r.path).meta("library_name") << " "
              << cur::Index(r.path).meta("library_version") << " into "
              << r.path.string() << " (" << r.compiled << " compiled, " << r.reused << " unchanged"
              << (r.resumed ? ", resumed from an interrupted build" : "") << (r.in_place ? ", updated in place" : "") << ")\n";
  return kExitOk;
}

int run_search(const Paths& p, const LibraryCommandOptions& o) {
  cur::SearchQuery q;
  q.words = o.words;
  q.family = o.family;
  q.limit = o.limit;
  if (!o.roughness.empty()) q.roughness = cur::parse_roughness_range(o.roughness);  // invalid_argument: exit 2
  if (const int rc = ensure_index(p, o.quiet, "library search")) return rc;
  const cur::Index idx(p.index);
  const auto hits = cur::search(idx, q);
  if (o.json) {
    auto arr = nlohmann::json::array();
    for (const auto& h : hits) {
      auto j = entry_json(h.entry);
      j["matched"] = h.why;
      j["matched_alias"] = h.matched_alias.empty() ? nlohmann::json(nullptr) : nlohmann::json(h.matched_alias);
      arr.push_back(j);
    }
    std::cout << arr.dump(2) << "\n";
  } else {
    std::size_t wn = 0, wf = 0;
    for (const auto& h : hits) wn = std::max(wn, h.entry.name.size()), wf = std::max(wf, h.entry.family.size());
    for (const auto& h : hits) {
      std::cout << pad(h.entry.name, wn) << "  " << pad(h.entry.family, wf) << "  roughness " << std::fixed
                << std::setprecision(2) << h.entry.roughness << std::defaultfloat << "  \"" << h.entry.describes << "\"";
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
  const cur::Index idx(p.index);
  const auto name = idx.resolve(o.name);
  if (!name) return unknown_entry(idx, o.name, "library show");
  const auto e = *idx.entry(*name);
  const auto statements = idx.statements(*name);
  const auto prov = idx.provenance(*name);
  if (o.json) {
    auto j = entry_json(e);
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
    std::cout << j.dump(2) << "\n";
    return kExitOk;
  }
  std::cout << e.name;
  if (!e.aliases.empty()) {
    std::string a;
    for (const auto& x : e.aliases) a += (a.empty() ? "" : ", ") + x;
    std::cout << "  (alias " << a << ")";
  }
  std::cout << "\n  describes  \"" << e.describes << "\"\n"
            << "  family     " << e.family << (e.family_title.empty() ? "" : " (" + e.family_title + ")") << "\n"
            << "  licence    " << e.licence << "\n"
            << "  file       " << cur::DisplayPaths(p.library).path_of(e.file) << " (library " << e.library_version << ")\n";
  if (!e.deprecated_by.empty()) std::cout << "  DEPRECATED replaced by " << e.deprecated_by << "\n";
  if (!e.likes.empty()) {
    std::string l;
    for (const auto& x : e.likes) l += (l.empty() ? "" : ", ") + x;
    std::cout << "  like       " << l << "\n";
  }
  std::cout << "perceptual coordinates (compiled on device " << idx.meta("device") << ")\n";
  if (e.max_lateral_force_N > 0) {
    std::cout << "  roughness              " << num(e.roughness) << " (ratio scale, " << idx.meta("roughness_map") << ")\n"
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
  std::cout << "statements (" << cur::DisplayPaths(p.library).path_of(e.file) << ")\n";
  for (const auto& s : statements) {
    std::cout << "  " << std::setw(3) << s.line << "  " << s.text << "\n";
    for (const auto& [k, t] : s.sources) std::cout << "         source " << k << " \"" << t << "\"\n";
  }
  std::cout << "resolution (every parameter: value in SI, layer, where it was said)\n";
  std::size_t wp = 0;
  for (const auto& r : prov) wp = std::max(wp, r.parameter.size());
  for (const auto& r : prov) {
    // As explain shows them (95 mm, 0 deg), not in raw SI: the JSON keeps value_si and si_unit.
    const std::string value = r.si_unit.empty() ? r.stated : schema::display_value(r.value_si, r.si_unit);
    std::cout << "  " << pad(r.parameter, wp) << "  " << pad(value, 12) << "  " << pad(r.layer, 10) << "  " << r.source << "\n";
    for (const auto& [k, t] : r.notes) std::cout << "      source " << k << " \"" << t << "\"\n";
  }
  return kExitOk;
}

int run_near(const Paths& p, const LibraryCommandOptions& o) {
  if (const int rc = ensure_index(p, o.quiet, "library near")) return rc;
  const cur::Index idx(p.index);
  const auto name = idx.resolve(o.name);
  if (!name) return unknown_entry(idx, o.name, "library near");
  const auto ns = cur::nearest(idx, *name, o.limit);
  if (o.json) {
    auto arr = nlohmann::json::array();
    for (const auto& n : ns)
      arr.push_back({{"name", n.entry.name}, {"family", n.entry.family}, {"roughness", n.entry.roughness},
                     {"distance_jnd", n.distance}, {"force_jnd", n.force_steps}, {"period_doublings", n.period_doublings},
                     {"why", n.why}});
    std::cout << nlohmann::json{{"from", *name}, {"weber_fraction", std::stod(idx.meta("weber_fraction"))}, {"nearest", arr}}.dump(2)
              << "\n";
    return kExitOk;
  }
  std::cout << "nearest to " << *name << " (distance in force JND steps of " << num(std::stod(idx.meta("weber_fraction")) * 100)
            << " %; a period doubling counts " << num(cur::kJndPerPeriodDoubling) << ", docs/LIBRARY.md)\n";
  std::size_t wn = 0;
  for (const auto& n : ns) wn = std::max(wn, n.entry.name.size());
  for (const auto& n : ns)
    std::cout << "  " << std::setw(6) << std::fixed << std::setprecision(1) << n.distance << std::defaultfloat << "  "
              << pad(n.entry.name, wn) << "  " << n.why << "\n";
  return kExitOk;
}

}  // namespace

void add_library_commands(CLI::App& library, LibraryCommandOptions& o) {
  o.check = library.add_subcommand("check", "validate every entry: metadata, sources, names, cycles, compiles on every device, JND collisions");
  add_paths(o.check, o, false);
  o.check->add_option("--device", o.devices, "check only these devices (default: every device of the calibration)");
  o.check->add_flag("--json", o.json, "print one JSON object with the diagnostics");
  o.check->add_flag("--quiet", o.quiet, "no progress on stderr");
  o.check->add_flag("--werror", o.werror, "warnings fail the check too");
  o.check->add_option("--root", o.root, "in a layered library (--library LAB:WORLD), check only the root with this id");

  o.index_cmd = library.add_subcommand("index", "build the SQLite index (atomically; a failed build leaves the old one)");
  add_paths(o.index_cmd, o, true);
  o.index_cmd->add_flag("--json", o.json, "print JSON");
  o.index_cmd->add_flag("--full", o.full, "compile every entry again (by default only entries whose inputs changed)");
  o.index_cmd->add_flag("--quiet", o.quiet, "no progress on stderr");

  o.search = library.add_subcommand("search", "find entries by name, alias, words and roughness range (exit 1 if none match)");
  o.search->add_option("words", o.words, "words to look for (name, alias, description, family, sources)");
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
  add_paths(o.near, o, true);
  o.near->add_flag("--json", o.json, "print JSON");
  o.near->add_flag("--quiet", o.quiet, "no progress if the index has to be built");
}

int cmd_library_sub(const CommonOptions& common, LibraryCommandOptions o) {
  const bool any = o.check->parsed() || o.index_cmd->parsed() || o.search->parsed() || o.show->parsed() || o.near->parsed();
  if (!any) return -1;
  o.json = o.json || common.json;
  try {
    const auto p = paths_of(common, o);
    if (o.check->parsed()) return run_check(p, o);
    if (o.index_cmd->parsed()) return one_root(p, "library index"), run_index(p, o);
    if (o.search->parsed()) return one_root(p, "library search"), run_search(p, o);
    if (o.show->parsed()) return one_root(p, "library show"), run_show(p, o);
    return one_root(p, "library near"), run_near(p, o);
  } catch (const cur::IndexError& e) {
    std::cerr << "sandpaper library: " << e.what() << "\n";
    return kExitUsage;
  }
}

}  // namespace sandpaper::cli
