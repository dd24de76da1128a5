#include "cmd_library_shared.hpp"

#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/curation/progress.hpp"

namespace sandpaper::cli::library_cmd {

// "1 entry", "2 entries".
std::string entries_text(std::size_t n) { return std::to_string(n) + (n == 1 ? " entry" : " entries"); }

std::string num(double v, int digits) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

std::string pad(const std::string& s, std::size_t w) { return s.size() >= w ? s : s + std::string(w - s.size(), ' '); }

void add_paths(CLI::App* sub, LibraryCommandOptions& o, bool index, bool here) {
  sub->add_option("--library", o.library_dir,
                  here ? "library folder, or folders front first as LAB:WORLD (default: the library of the working directory: the "
                         "nearest folder above holding library.toml, or library/ at the top of its git work tree)"
                       : "library folder, or folders front first as LAB:WORLD (default: $SANDPAPER_LIBRARY_PATH, $SANDPAPER_LIBRARY, "
                         "$SANDPAPER_DATA_DIR/library, or the shipped library)");
  sub->add_option("--calibration", o.calibration_dir, "calibration folder (default: $SANDPAPER_CALIBRATION, $SANDPAPER_DATA_DIR/calibration, or the shipped calibration)");
  if (index)
    sub->add_option("--index", o.index, "SQLite index file (default: $SANDPAPER_LIBRARY_INDEX or <library>/.index/library.sqlite)");
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

namespace {

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

}  // namespace

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

}  // namespace sandpaper::cli::library_cmd
