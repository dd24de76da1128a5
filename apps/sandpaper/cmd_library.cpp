#include "cmd_library.hpp"
#include "cmd_library_shared.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <system_error>

#include <CLI/CLI.hpp>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/schema/json_text.hpp"
#include "sandpaper/schema/patch_json.hpp"
#include "sandpaper/curation/check.hpp"
#include "sandpaper/compiler/display_paths.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/layers.hpp"
#include "sandpaper/curation/library_here.hpp"
#include "sandpaper/curation/review.hpp"

namespace sandpaper::cli {

namespace library_cmd {

int run_check(const Paths& p, const LibraryCommandOptions& o) {
  auto progress = cur::Progress::on_stderr("checking", 0, o.quiet);  // check_library counts the entries
  cur::CheckOptions co{p.library, p.calibration, o.devices, p.roots, o.root};
  const auto r = cur::check_library(co, progress);
  const bool failed = r.errors() > 0 || (o.werror && r.warnings() > 0);
  progress.clear();
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
  auto progress = cur::Progress::on_stderr("checking", 0, o.quiet);  // check_library counts the entries
  const auto r = cur::review_library({p.library, p.calibration, o.devices, o.base}, progress);
  progress.clear();
  if (!r.error.empty()) {  // not a work tree, a base git does not have: what to review is not known
    std::cerr << "sandpaper library review: " << r.error << "\n";
    return kExitUsage;
  }
  progress.finish("checked " + entries_text(progress.done()) + " on " + std::to_string(r.devices) + " device" +
                  (r.devices == 1 ? "" : "s"));
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

}  // namespace library_cmd

using namespace library_cmd;

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
  add_paths(o.check, o, false, true);
  o.check->add_option("--device", o.devices, "check only these devices (default: every device of the calibration)");
  o.check->add_flag("--json", o.json, "print one JSON object with the diagnostics");
  o.check->add_flag("--quiet", o.quiet, "no progress on stderr");
  o.check->add_flag("--werror", o.werror, "warnings fail the check too");
  o.check->add_option("--root", o.root, "in a layered library (--library LAB:WORLD), check only the root with this id");

  o.review = library.add_subcommand("review",
                                    "review a change to a library in git: check what changed since --base (and what is built on it) on "
                                    "every device; fail on errors and on new warnings not accepted; list what a person must look at");
  add_paths(o.review, o, false, true);
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

  o.near = library.add_subcommand("near", "the perceptually nearest entries, with the distance in JNDs (each dimension its percept's) and why");
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
  // check and review judge the files a curator edits: the library of the folder they run in, never
  // the one this program was built with, which would pass whatever the curator changed.
  if ((o.check->parsed() || o.review->parsed()) && o.library_dir.empty() && common.library_dir.empty()) {
    const char* who = o.check->parsed() ? "library check" : "library review";
    std::error_code ec;
    const auto cwd = std::filesystem::current_path(ec);
    std::optional<std::filesystem::path> here;
    if (!ec) here = cur::library_around(cwd);
    if (!here) {
      std::cerr << "sandpaper " << who << ": no library here: no folder from " << (ec ? std::string(".") : cwd.string())
                << " up holds library.toml, and the top of its git work tree has no library/library.toml. Pass --library DIR "
                << "(the folder holding library.toml), or cd into the library. (" << who
                << " does not take $SANDPAPER_LIBRARY_PATH, $SANDPAPER_LIBRARY or the library Sandpaper was built with: "
                << "it judges the files you are changing.)\n";
      return kExitUsage;
    }
    o.library_dir = here->string();
  }
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
