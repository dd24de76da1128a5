// `library check`: each check below names its code; docs/LIBRARY.md, "What check checks", lists them.
#include "sandpaper/curation/check.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <tuple>
#include <map>
#include <set>
#include <sstream>

#include "sandpaper/schema/confined_path.hpp"
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/display_paths.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/percepts.hpp"
#include "entry_checker.hpp"
#include "first_added.hpp"
#include "sqlite_util.hpp"

namespace sandpaper::curation {

using compiler::Diagnostic;
using compiler::Diagnostics;
using compiler::LibraryEntry;
using compiler::SourceLocation;

std::size_t CheckResult::errors() const {
  return static_cast<std::size_t>(std::count_if(diagnostics.all().begin(), diagnostics.all().end(),
                                                [](const Diagnostic& d) { return d.severity == compiler::Severity::Error; }));
}
std::size_t CheckResult::warnings() const {
  return static_cast<std::size_t>(std::count_if(diagnostics.all().begin(), diagnostics.all().end(),
                                                [](const Diagnostic& d) { return d.severity == compiler::Severity::Warning; }));
}
std::string CheckResult::summary() const {
  auto plural = [](std::size_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); };
  std::string unc;
  for (const auto& d : uncalibrated) unc += (unc.empty() ? " (uncalibrated, W0331: " : ", ") + d;
  return "checked " + plural(entries, "entry", "entries") + " on " + plural(devices.size(), "device", "devices") +
         (unc.empty() ? "" : unc + ")") + ": " +
         plural(errors(), "error", "errors") + ", " + plural(warnings(), "warning", "warnings") +
         (accepted.all().empty() ? "" : ", " + std::to_string(accepted.all().size()) + " accepted");
}

using check_detail::Checker;
using check_detail::fmt;
using check_detail::quoted;

namespace {

// A compile failure's signature, to say once for all devices that fail the same way.
std::string signature(const Diagnostics& d) {
  std::string s;
  for (const auto& x : d.all())
    if (x.severity == compiler::Severity::Error) s += x.code + ":" + x.message + "\n";
  return s;
}

}  // namespace

namespace {

// check's own warnings (W0601, W0603, W0612, ...) at an entry's file that the entry accepts move to
// result.accepted, as the compiler moves its own; then an `accept` no warning needed is W0614
// (the warning went away, or never was, and a later one of that code would be hidden unseen).
void accept_check_warnings(const compiler::Library& lib, const compiler::DisplayPaths& disp, const Checker& ck,
                           std::map<const LibraryEntry*, std::set<std::string>>& accepted_by, CheckResult& result) {
  std::map<std::string, const LibraryEntry*> by_file;
  for (const auto& e : lib.entries())
    if (e.root == 0) by_file[disp.path_of(e)] = &e;
  const auto accept_of = [](const LibraryEntry& e, const std::string& code) -> const compiler::AcceptStmt* {
    for (const auto& st : e.syntax.statements)
      if (const auto* a = std::get_if<compiler::AcceptStmt>(&st.node); a && a->code == code) return a;
    return nullptr;
  };
  Diagnostics kept;
  for (const auto& d : result.diagnostics.all()) {
    const auto it = d.severity == compiler::Severity::Warning && d.location.file ? by_file.find(d.location.file->name) : by_file.end();
    const auto* a = it != by_file.end() ? accept_of(*it->second, d.code) : nullptr;
    Diagnostics one;
    if (a) {
      auto& x = one.accepted(schema::Code::of(d.code), d.location, "accepted: " + d.message, d.suggestion);
      x.notes = d.notes;
      x.notes.push_back({ck.at(a->location), "accepted here: \"" + a->reason + "\""});
      result.accepted.append(one);
      accepted_by[it->second].insert(d.code);
      continue;
    }
    // (An E0009 / W0009 "too many" line is kept as it was: what it counts was not kept to move.)
    auto& x = d.severity == compiler::Severity::Error ? one.error(schema::Code::of(d.code), d.location, d.message, d.suggestion)
                                                      : one.warning(schema::Code::of(d.code), d.location, d.message, d.suggestion);
    x.notes = d.notes;
    kept.append(one);
  }
  for (const auto& [e, codes] : accepted_by)
    for (const auto& st : e->syntax.statements)
      if (const auto* a = std::get_if<compiler::AcceptStmt>(&st.node); a && !codes.count(a->code))
        kept.warning("W0614", ck.at(a->location),
                     quoted(e->name) + " accepts " + a->code + ", but neither a device's compile nor `library check` gives it that warning",
                     "remove the line: an `accept` with nothing to accept would hide a later " + a->code + " unseen");
  result.diagnostics = std::move(kept);
}

// The files the front root's index lists, each as owner of its entry's name; none if the root has
// no index of this schema, or one of another folder.
std::set<std::string> indexed_files(const std::vector<std::filesystem::path>& roots) {
  std::set<std::string> out;
  try {
    const Index idx(roots.size() > 1 ? layer_index_path(roots.front()) : default_index_path(roots.front()));
    if (idx.meta("library_dir") != std::filesystem::absolute(roots.front()).lexically_normal().string()) return out;
    sql::Stmt files(idx.handle(), "SELECT file FROM entries");
    while (files.step()) out.insert(files.text(0));
  } catch (const std::exception&) {
  }
  return out;
}

// Checks the front root of `roots` against the roots below it.
void check_front_root(const std::vector<std::filesystem::path>& roots, const std::filesystem::path& cal_dir,
                      const calibration::CalibrationSet& cal, CheckResult& result, Progress& progress,
                      const std::optional<std::set<std::string>>& established) {
  // One read of the library, shared by the per-device compilers below (at 100,000 entries each copy
  // is about 2 GB).
  const auto shared = std::make_shared<const compiler::Library>(roots);
  const compiler::Library& lib = *shared;
  const compiler::DisplayPaths disp(lib);
  auto& out = result.diagnostics;
  for (const auto& e : lib.entries()) result.entries += e.root == 0;
  Checker ck{lib, disp, out};
  ck.indexed_files = established ? *established : indexed_files(roots);
  // Not told which files were there before (a review is): git's history says which came first, so a
  // fresh clone, which has no index, blames the newcomer as the curator's machine does.
  if (!established)
    ck.history = [root = roots.front()](const std::vector<std::string>& files) { return first_added(root, files); };

  // The manifest and the entries' syntax (E0601, the compiler's E01xx/E02xx): the front root's.
  {
    Diagnostics front;
    const std::string prefix = lib.layered() ? "library/" + lib.roots().front().id + "/" : "library/";
    for (const auto& d : lib.scan_diagnostics().all())
      if (!lib.layered() || (d.location.file && (d.location.file->name.rfind(prefix, 0) == 0 ||
                                                 d.location.file->name == "library/library.toml")))
        front.append([&] {
          Diagnostics one;
          auto& x = d.severity == compiler::Severity::Error ? one.error(schema::Code::of(d.code), d.location, d.message, d.suggestion)
                                                            : one.warning(schema::Code::of(d.code), d.location, d.message, d.suggestion);
          x.notes = d.notes;
          return one;
        }());
    disp.append_relocated(out, front);
  }
  const auto manifest_loc = [&] {
    SourceLocation l;
    l.file = std::make_shared<const compiler::SourceFile>(disp.path_of("library.toml"), "");
    return l;
  };
  if (lib.roots().front().manifest.file.empty())
    out.error("E0601", manifest_loc(), "the library has no library.toml",
              "add library.toml with name, version and [families.<id>] tables (docs/LIBRARY.md)");
  else if (const auto& ref = lib.manifest().reference; !ref.empty() && !lib.entry(ref))
    out.error("E0611", manifest_loc(), "library.toml's reference " + quoted(ref) + " is not an entry of the library",
              "name the entry a bare perceptual description starts from (a grating the roughness map was measured on)");

  for (const auto& e : lib.entries())
    if (e.root == 0 && e.parsed_ok) ck.metadata(e), ck.sources(e), ck.images(e), ck.shadowing(e);
  ck.duplicates();
  ck.deprecations();
  const auto in_cycle = ck.cycles();

  // Entries that cannot be compiled meaningfully: syntax errors, `like` cycles, and whatever starts
  // from them (their own errors are reported already; fix those first).
  std::set<std::string> broken = in_cycle;  // qualified names
  for (const auto& e : lib.entries())
    if (!e.parsed_ok) broken.insert(lib.qualified_name(e));
  for (bool grew = true; grew;) {
    grew = false;
    for (const auto& e : lib.entries()) {
      if (broken.count(lib.qualified_name(e))) continue;
      for (const auto& l : e.likes)
        if (const auto* to = lib.entry(l); to && broken.count(lib.qualified_name(*to))) {
          broken.insert(lib.qualified_name(e)), grew = true;
          break;
        }
    }
  }

  // E0610: every entry compiles for every device. Coordinates for the JND check come from `sim`
  // (or the first device).
  std::vector<compiler::Compiler> compilers;
  for (const auto& d : result.devices) compilers.emplace_back(compiler::CompileOptions{d, {}, cal_dir, roots}, shared);
  std::size_t coord_device = 0;
  for (std::size_t i = 0; i < result.devices.size(); ++i)
    if (result.devices[i] == "sim") coord_device = i;
  std::map<std::string, Percepts> percepts;
  // The warning codes each compiled entry accepts and that a warning needed (see accept_check_warnings).
  std::map<const LibraryEntry*, std::set<std::string>> accepted_by;
  for (const auto& e : lib.entries()) {
    if (e.root != 0) continue;
    if (broken.count(lib.qualified_name(e)) || !ck.owns_name(e)) {
      progress.step(e.name);
      continue;
    }
    // (signature, devices, diagnostics) of each distinct failure.
    std::vector<std::tuple<std::string, std::vector<std::string>, Diagnostics>> failures;
    // Every warning the compiler gives the entry, on any device (what explain would say): one
    // that reads the same on every device is said once; else each says on which devices.
    std::vector<std::pair<Diagnostic, std::vector<std::string>>> warnings;
    const auto own_file = lib.source_name(e);
    for (std::size_t i = 0; i < compilers.size(); ++i) {
      const auto r = compilers[i].compile_file(disp.path_of(e));
      for (const auto& w : r.diagnostics.all()) {
        if (w.severity == compiler::Severity::Error) continue;  // a note here is an accepted warning
        // The device's, not the entry's: said once, in the summary.
        if (w.code == "W0331") {
          result.uncalibrated.insert(result.devices[i]);
          continue;
        }
        // A warning at another entry's statement (one this entry inherits) is that entry's to see.
        if (w.location.file && w.location.file->name != own_file && w.location.file->name.rfind("library/", 0) == 0) continue;
        auto it = std::find_if(warnings.begin(), warnings.end(), [&](const auto& x) {
          return x.first.code == w.code && x.first.message == w.message && x.first.location.str() == w.location.str();
        });
        if (it != warnings.end()) it->second.push_back(result.devices[i]);
        else warnings.emplace_back(w, std::vector<std::string>{result.devices[i]});
      }
      if (r.ok()) {
        if (i == coord_device && r.material) percepts[e.name] = percepts_of(*r.material, *r.program, cal);
        continue;
      }
      const auto sig = signature(r.diagnostics);
      auto it = std::find_if(failures.begin(), failures.end(), [&](const auto& f) { return std::get<0>(f) == sig; });
      if (it != failures.end()) std::get<1>(*it).push_back(result.devices[i]);
      else failures.emplace_back(sig, std::vector<std::string>{result.devices[i]}, r.diagnostics);
    }
    std::set<std::string> accepted_codes;
    for (const auto& [w, devices] : warnings) {
      if (w.severity == compiler::Severity::Note) accepted_codes.insert(w.code);
      std::string on;
      if (devices.size() < result.devices.size())
        for (const auto& d : devices) on += (on.empty() ? " (on device " : ", ") + quoted(d);
      auto moved = disp.relocate(w);
      Diagnostics one;
      const auto message = moved.message + (on.empty() ? "" : on + ")");
      (w.severity == compiler::Severity::Note ? one.accepted(schema::Code::of(moved.code), moved.location, message, moved.suggestion)
                                              : one.warning(schema::Code::of(moved.code), moved.location, message, moved.suggestion))
          .notes = moved.notes;
      (w.severity == compiler::Severity::Note ? result.accepted : out).append(one);
    }
    if (failures.empty()) accepted_by[&e] = std::move(accepted_codes);
    for (const auto& [sig, devices, diags] : failures) {
      std::string which, files;
      for (const auto& d : devices) {
        which += (which.empty() ? "" : ", ") + quoted(d);
        files += (files.empty() ? "" : ", ") + cal.find_device(d)->file;
      }
      std::string help;
      for (const auto& x : diags.all())
        if (x.severity == compiler::Severity::Error && !x.suggestion.empty() && help.empty()) help = x.suggestion;
      auto& d = out.error("E0610", ck.entry_loc(e),
                          quoted(e.name) + " does not compile for device" + (devices.size() > 1 ? "s " : " ") + which + " (" +
                              files + ")",
                          (help.empty() ? std::string("fix what the compiler says below") : help) +
                              "; every entry must play on every shipped device (`sandpaper explain --device " + devices.front() +
                              " " + disp.path_of(e) + "` shows the details)");
      for (const auto& x : diags.all()) {
        if (x.severity != compiler::Severity::Error) continue;
        const auto moved = disp.relocate(x);
        d.notes.push_back({moved.location, "error[" + moved.code + "]: " + moved.message +
                                               (moved.suggestion.empty() ? "" : " (help: " + moved.suggestion + ")")});
      }
    }
    progress.step(e.name);
  }

  // W0601: entries of one family that the thesis' knowledge cannot tell apart.
  const auto& jnd = cal.knowledge().force_jnd;
  std::vector<const LibraryEntry*> entries;
  for (const auto& e : lib.entries())
    if (e.root == 0) entries.push_back(&e);
  // Only pairs less than one force JND apart can collide: sorted by family and force, each entry
  // is compared with the entries just above it, not with the whole family (100,000 entries).
  // A dense family still has tens of millions of such pairs (60,000 generated gratings over a few
  // dozen JND): each is looked at through pointers, never by name, and not kept.
  std::vector<std::size_t> order;
  std::vector<const Percepts*> pc(entries.size(), nullptr);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const auto& a = *entries[i];
    auto pa = percepts.find(a.name);
    if (pa == percepts.end() || !pa->second.has_texture() || !a.deprecated_by.empty() || a.family.empty()) continue;
    if (const auto* fam = lib.manifest().family(a.family); fam && fam->stimulus_set) continue;
    pc[i] = &pa->second;
    order.push_back(i);
  }
  auto force = [&](std::size_t i) { return pc[i]->max_lateral_force_N; };
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return entries[x]->family != entries[y]->family ? entries[x]->family < entries[y]->family : force(x) < force(y);
  });
  // One warning an entry, on the later of a pair in name order (i < j), naming its nearest look-alike:
  // a curator needs each entry's worst pair, not every one (the notes name up to kMaxLookAlikeNotes,
  // then a count). Per entry: how many look-alikes, and the nearest few by (JND steps, name order).
  constexpr std::size_t kMaxLookAlikeNotes = 3;
  struct LookAlikes {
    std::size_t count = 0;
    std::vector<std::pair<double, std::size_t>> nearest;  // sorted, at most kMaxLookAlikeNotes + 1
  };
  std::vector<LookAlikes> alike(entries.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    for (std::size_t m = k + 1; m < order.size() && entries[order[m]]->family == entries[order[k]]->family; ++m) {
      if (!(jnd.steps_between(force(order[k]), force(order[m])) < 1.0)) break;
      const std::size_t i = std::min(order[k], order[m]), j = std::max(order[k], order[m]);
      double steps = 0;
      if (!indistinguishable(*pc[i], *pc[j], jnd, &steps)) continue;
      auto& a = alike[j];
      ++a.count;
      const std::pair<double, std::size_t> p{std::abs(steps), i};
      if (a.nearest.size() > kMaxLookAlikeNotes && !(p < a.nearest.back())) continue;
      a.nearest.insert(std::upper_bound(a.nearest.begin(), a.nearest.end(), p), p);
      if (a.nearest.size() > kMaxLookAlikeNotes + 1) a.nearest.pop_back();
    }
  for (std::size_t j = 0; j < alike.size(); ++j) {
    if (alike[j].count == 0) continue;
    const auto& partners = alike[j].nearest;
    const auto& a = *entries[partners.front().second];
    const auto& b = *entries[j];
    const auto& A = *pc[partners.front().second];
    const auto& B = *pc[j];
    const double steps = partners.front().first;
    const std::size_t more = alike[j].count - 1;
    auto& d = out.warning(
        "W0601", ck.entry_loc(b),
        quoted(b.name) + " may feel the same as " + quoted(a.name) + " (family " + a.family + "): maximum lateral forces " +
            fmt(B.max_lateral_force_N) + " and " + fmt(A.max_lateral_force_N) + " N are " + fmt(steps, 2) +
            " force JND apart (" + fmt(jnd.weber_fraction * 100) + " %, " + jnd.file + "; Minsky 1995 5.4.2), both " +
            A.texture_kind + "s of period class " + quoted(A.period_class) + " (" + fmt(A.period_m * 1000) + " and " +
            fmt(B.period_m * 1000) + " mm; 6.3.6)" +
            (more == 0 ? std::string()
                       : "; " + std::to_string(more) + " more entr" + (more == 1 ? "y" : "ies") +
                             " of the family, earlier in name order, " + (more == 1 ? "is" : "are") + " also within one force JND"),
        "make them differ by at least one force JND (a roughness further apart) or in period class, or deprecate one; "
        "if both are wanted (the thesis' own stimuli share force levels), accept it in the entry: accept W0601 \"why both\"");
    for (std::size_t k = 0; k < partners.size(); ++k)
      d.notes.push_back({ck.entry_loc(*entries[partners[k].second]), quoted(entries[partners[k].second]->name) + " is here"});
  }
  accept_check_warnings(lib, disp, ck, accepted_by, result);
}

}  // namespace

CheckResult check_library(const CheckOptions& options, Progress& progress) {
  CheckResult result;
  const auto cal_dir = options.calibration_dir.empty() ? calibration::default_calibration_dir() : options.calibration_dir;
  const auto cal = calibration::CalibrationSet::load(cal_dir);
  if (options.devices.empty())
    for (const auto& d : cal.devices()) result.devices.push_back(d.name);
  else
    result.devices = options.devices;
  for (const auto& d : result.devices)
    if (!cal.find_device(d)) throw std::invalid_argument("no device '" + d + "' in " + cal_dir.string() + "/devices");
  const std::vector<std::filesystem::path> roots =
      !options.library_path.empty() ? options.library_path
      : !options.library_dir.empty() ? std::vector<std::filesystem::path>{options.library_dir}
                                     : std::vector<std::filesystem::path>{compiler::default_library_dir()};
  // E0613: `like ID:NAME` needs every root's id to be its own.
  const compiler::Library whole(roots);
  std::map<std::string, std::filesystem::path> ids;
  bool root_found = options.root.empty();
  for (const auto& r : whole.roots()) {
    root_found = root_found || r.id == options.root;
    if (auto [it, fresh] = ids.emplace(r.id, r.dir); !fresh) {
      SourceLocation at;
      at.file = std::make_shared<const compiler::SourceFile>((r.dir / "library.toml").string(), "");
      result.diagnostics.error("E0613", at,
                               "two roots of the library path are both named '" + r.id + "' (" + it->second.string() + " and " +
                                   r.dir.string() + ")",
                               "give one of them another id in its library.toml (id = \"lab\"); `like ID:NAME` names a root by it");
    }
  }
  if (!root_found) {
    std::string listed;
    for (const auto& r : whole.roots()) listed += (listed.empty() ? "'" : ", '") + r.id + "'";
    throw std::invalid_argument("no root named '" + options.root + "' in the library path: its roots are " + listed +
                                " (a root's id is `id` in its library.toml, else its folder's name)");
  }
  // How many entries the check goes through, for the progress counter.
  std::size_t total = 0;
  for (const auto& e : whole.entries())
    if (options.root.empty() || whole.roots()[e.root].id == options.root) total += 1;
  progress.set_total(total);
  for (std::size_t i = 0; i < roots.size(); ++i)
    if (options.root.empty() || whole.roots()[i].id == options.root)
      check_front_root(std::vector<std::filesystem::path>(roots.begin() + static_cast<std::ptrdiff_t>(i), roots.end()), cal_dir,
                       cal, result, progress, i == 0 ? options.established : std::nullopt);
  return result;
}

}  // namespace sandpaper::curation
