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
#include "sandpaper/curation/display.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/percepts.hpp"
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

namespace {

std::string quoted(const std::string& s) { return "'" + s + "'"; }

std::string fmt(double v, int digits = 3) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

struct Checker {
  const compiler::Library& lib;
  const DisplayPaths& disp;
  Diagnostics& out;
  // The front root's files that its index (if it has one, of this folder) lists as owning their
  // names: in a clash of names these are the established entries, and the other file is the newcomer.
  std::set<std::string> indexed_files = {};
  std::set<std::string> images_seen = {};  // images whose licence is checked

  // Whether `name` is taken in the front root, as a name or an alias.
  bool taken(const std::string& name) const {
    for (const auto& e : lib.entries()) {
      if (e.root != 0) continue;
      if (e.name == name || e.syntax.name == name) return true;
      for (const auto& a : e.aliases)
        if (a == name) return true;
    }
    return false;
  }
  // A name no entry of the front root has: NAME-2, NAME-3, ...
  std::string free_name(const std::string& name) const {
    for (int i = 2;; ++i)
      if (const auto n = name + "-" + std::to_string(i); !taken(n)) return n;
  }

  SourceLocation at(const SourceLocation& loc) const { return disp.relocate(loc); }
  // The entry its root resolves its name to (not a second file with a name the root already has).
  bool owns_name(const LibraryEntry& e) const { return lib.entry(lib.qualified_name(e)) == &e; }

  // W0612/W0613: an entry of the front root that hides one below says so with `overrides`.
  void shadowing(const LibraryEntry& e) {
    const auto* below = lib.shadowed_by(e);
    if (below && !e.overrides) {
      auto& d = out.warning("W0612", entry_loc(e),
                            quoted(lib.qualified_name(e)) + " hides " + quoted(lib.qualified_name(*below)) +
                                ": `like " + (below->name == e.name ? e.name : below->name) + "` now finds this entry, not the one below",
                            "if that is meant, add `overrides` to this entry; else rename it (names are looked up front to back)");
      d.notes.push_back({entry_loc(*below), quoted(lib.qualified_name(*below)) + " is here"});
    } else if (!below && e.overrides) {
      for (const auto& st : e.syntax.statements)
        if (std::holds_alternative<compiler::OverridesStmt>(st.node))
          out.warning("W0613", at(std::get<compiler::OverridesStmt>(st.node).location),
                      quoted(e.name) + " says `overrides`, but no library root below has an entry of that name",
                      "remove `overrides`, or check the library path's order (front first: --library LAB:WORLD)");
    }
  }
  // Where to point for something about the entry as a whole: its name, else the file's start.
  SourceLocation entry_loc(const LibraryEntry& e) const {
    if (e.syntax.name_location.file) return at(e.syntax.name_location);
    SourceLocation l;
    l.file = e.syntax.file;
    l.line = 1;
    l.column = 1;
    return at(l);
  }

  void metadata(const LibraryEntry& e) {
    const auto where = entry_loc(e);
    if (e.syntax.name.empty()) {
      out.error("E0602", where, "library entry " + e.relative_path + " has no `material \"" + e.name + "\" { ... }` block",
                "wrap the statements in material \"" + e.name + "\" { ... }: a library entry is named by its file stem");
    } else if (e.syntax.name != e.name) {
      // Renaming the file to a name another entry has would only trade this error for E0607.
      const bool other_has_it = lib.entry(e.syntax.name) != nullptr && lib.entry(e.syntax.name) != &e;
      out.error("E0602", where, "material " + quoted(e.syntax.name) + " is in a file named " + quoted(e.name + ".hmat"),
                other_has_it ? "write material \"" + e.name + "\": an entry's name is its file stem, so `like` finds it ('" +
                                   e.syntax.name + "' is another entry's name already)"
                             : "write material \"" + e.name + "\", or rename the file to " + e.syntax.name +
                                   ".hmat: an entry's name is its file stem, so `like` finds it");
    }
    if (e.describes.empty())
      out.error("E0603", where, "library entry " + quoted(e.name) + " has no `describes`",
                "add describes \"...\": one line saying what real material or stimulus it is");
    const auto& m = lib.manifest();
    const compiler::FamilyStmt* fam = nullptr;
    const compiler::LicenceStmt* lic = nullptr;
    std::map<std::string, SourceLocation> own_aliases;
    for (const auto& st : e.syntax.statements) {
      if (const auto* f = std::get_if<compiler::FamilyStmt>(&st.node)) fam = f;
      if (const auto* l = std::get_if<compiler::LicenceStmt>(&st.node)) lic = l;
      if (const auto* a = std::get_if<compiler::AliasStmt>(&st.node)) {
        if (a->name == e.name) {
          out.error("E0607", at(a->location), "alias " + quoted(a->name) + " repeats the entry's own name",
                    "remove the alias: the name already finds the entry");
        } else if (auto it = own_aliases.find(a->name); it != own_aliases.end()) {
          auto& d = out.error("E0607", at(a->location), "alias " + quoted(a->name) + " is given twice", "remove one of the two");
          d.notes.push_back({at(it->second), "first given here"});
        } else {
          own_aliases.emplace(a->name, a->location);
        }
      }
    }
    std::vector<std::string> ids;
    for (const auto& f : m.families) ids.push_back(f.id);
    if (!fam) {
      out.error("E0604", where, "library entry " + quoted(e.name) + " has no `family`",
                ids.empty() ? std::string("declare families in library.toml ([families.<id>]) and add family <id>")
                            : "add family <id>, one of: " + join(ids));
    } else if (!m.family(fam->family)) {
      const auto guess = compiler::closest_match(fam->family, ids);
      out.error("E0604", at(fam->location), "family " + quoted(fam->family) + " is not declared in library.toml",
                guess.empty() ? (ids.empty() ? std::string("add [families.") + fam->family + "] with title and describes to library.toml"
                                             : "use one of: " + join(ids) + ", or add [families." + fam->family + "] to library.toml")
                              : "did you mean `" + guess + "`? (or add [families." + fam->family + "] to library.toml)");
    }
    if (!lic || lic->licence.empty()) {
      out.error("E0605", lic ? at(lic->location) : where, "library entry " + quoted(e.name) + " has no licence",
                "add licence \"CC0-1.0\" (or another SPDX id, https://spdx.org/licenses/): entries are shared");
    } else {
      auto loc = lic->location;
      loc.column += 1;  // past the opening quote: the expression's offsets count from its first character
      licence_text(lic->licence, loc, "licence");
    }
  }

  // E0605 / W0603 for an SPDX expression written at `loc` (its first character): where it does not
  // parse, and each id the check does not know, with "did you mean".
  void licence_text(const std::string& text, SourceLocation loc, const std::string& what) {
    const auto ex = parse_licence_expression(text);
    if (!ex.ok()) {
      auto l = loc;
      l.column += static_cast<int>(ex.error_at);
      out.error("E0605", at(l), what + " " + quoted(text) + " is not an SPDX licence id or expression: " + ex.error,
                "write an SPDX id such as \"CC0-1.0\" or \"CC-BY-4.0\", or ids joined by AND, OR, WITH and parentheses "
                "(\"CC-BY-SA-4.0 AND CC0-1.0\"; https://spdx.org/licenses/)");
      return;
    }
    std::size_t from = 0;
    for (const auto& id : ex.ids) {
      if (known_licence(id)) continue;
      auto l = loc;
      const auto off = text.find(id, from);
      if (off != std::string::npos) l.column += static_cast<int>(off), l.length = static_cast<int>(id.size()), from = off + id.size();
      const auto guess = licence_guess(id);
      out.warning("W0603", at(l), what + " id " + quoted(id) + " is not one library check knows",
                  guess.empty() ? "check the id at https://spdx.org/licenses/ (use LicenseRef-... for a licence outside SPDX)"
                                : "did you mean \"" + guess + "\"?");
    }
  }

  // E0615: an image names its licence and credit in a REUSE sidecar (<image>.license); said once an image.
  void image_licence(const LibraryEntry& e, const compiler::HeightmapStmt& h, const std::filesystem::path& inside) {
    const auto image = lib.roots()[e.root].dir / inside;
    if (!images_seen.insert(image.lexically_normal().string()).second) return;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(image, ec)) return;  // the compiler's E0314 / missing-image error says so
    const auto shown = disp.path_of(inside.generic_string());
    const auto side = read_image_licence(image);
    const std::string form = "SPDX-License-Identifier: CC0-1.0\nSPDX-FileCopyrightText: who made the image, and where it is from";
    if (!side) {
      out.error("E0615", at(h.path_location), "image " + quoted(h.path) + " has no licence: there is no " + shown + ".license",
                "write " + shown + ".license (REUSE) with two lines:\n" + form);
      return;
    }
    std::ifstream in(side->sidecar, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto file = std::make_shared<const compiler::SourceFile>(shown + ".license", text.substr(0, 64 * 1024));
    SourceLocation top;
    top.file = file;
    top.line = 1;
    top.column = 1;
    if (side->licence.empty())
      out.error("E0615", top, "image " + quoted(h.path) + "'s licence file has no SPDX-License-Identifier", "add a line:\n" + form.substr(0, form.find('\n')));
    if (side->credit.empty())
      out.error("E0615", top, "image " + quoted(h.path) + "'s licence file has no SPDX-FileCopyrightText (the credit)",
                "add a line: SPDX-FileCopyrightText: who made the image, and where it is from");
    if (!side->licence.empty()) {
      SourceLocation l;
      l.file = file;
      l.line = side->licence_line;
      const auto line = file->line_text(side->licence_line);
      l.column = static_cast<int>(line.find(side->licence)) + 1;
      l.length = static_cast<int>(side->licence.size());
      licence_text(side->licence, l, "image licence");
    }
  }

  // E0606: every statement that carries a number names where it comes from.
  void sources(const LibraryEntry& e) {
    for (const auto& st : e.syntax.statements)
      if (compiler::carries_numbers(st) && st.sources.empty())
        out.error("E0606", at(st.location), "`" + st.keyword + "` carries numbers but has no `source`",
                  "add a line after it: source KIND \"where the numbers come from\", KIND one of measurement, standard, "
                  "publication, derived (show the arithmetic), by-ear (designed by ear or eye, said plainly)");
  }

  // E0612: an entry's image lies inside the library. The library is shared: an absolute path, one
  // that climbs out, or a symbolic link that leads out reads whatever the compiling machine has there,
  // and would name it in patches. Links are followed as the compiler follows them (schema::confined_path).
  void images(const LibraryEntry& e) {
    for (const auto& st : e.syntax.statements) {
      const auto* h = std::get_if<compiler::HeightmapStmt>(&st.node);
      if (!h) continue;
      const std::filesystem::path p(h->path);
      const auto inside = (std::filesystem::path(e.relative_path).parent_path() / p).lexically_normal();
      std::string why;
      if (p.is_absolute() || inside.empty() || *inside.begin() == "..") {
        why = "is outside the library";
      } else {
        try {
          schema::confined_path(lib.roots()[e.root].dir, inside.generic_string(), "the library");
        } catch (const schema::OutsideFolder&) {
          why = "is a symbolic link, or lies under one, that leads outside the library";
        }
      }
      if (!why.empty())
        out.error("E0612", at(h->path_location), "image " + quoted(h->path) + " " + why,
                  "copy the image into the library (library/images/) and name it relative to the entry's folder, "
                  "e.g. \"../images/NAME.png\"");
      else
        image_licence(e, *h, inside);
    }
  }

  static std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  }

  // E0607: a name or alias that another entry already uses.
  void duplicates() {
    struct First {
      const LibraryEntry* entry;
      SourceLocation loc;
      bool alias;
    };
    std::map<std::string, First> seen;
    auto claim = [&](const std::string& token, const LibraryEntry& e, const SourceLocation& loc, bool alias) {
      auto [it, fresh] = seen.emplace(token, First{&e, loc, alias});
      if (fresh || it->second.entry == &e) return;
      const auto& f = it->second;
      const std::string first_as = f.alias ? "an alias of " + quoted(f.entry->name) : "the name of " + f.entry->relative_path;
      const bool indexed = indexed_files.count(f.entry->relative_path) > 0;
      const auto free = free_name(token);
      const auto dir = std::filesystem::path(e.relative_path).parent_path().string();
      auto& d = out.error("E0607", at(loc),
                          std::string(alias ? "alias " : "name ") + quoted(token) + " is already " + first_as +
                              (indexed ? " (in the library's index)" : ""),
                          alias ? "names and aliases are unique across the whole library: remove this alias, or say one that is free (" +
                                      quoted(free) + " is)"
                                : "names are unique across the whole library (not per family): rename this file and its material "
                                  "to a free name that says how it differs, for instance " +
                                      (dir.empty() ? "" : dir + "/") + free + ".hmat with material \"" + free + "\"");
      d.notes.push_back({at(f.loc), f.alias ? "the alias of " + quoted(f.entry->name) : "the other entry named " + quoted(token)});
    };
    // The established entries (those the index has) claim first, then the others in path order:
    // the error lands on the newcomer, the file a reviewer is looking at.
    std::vector<const LibraryEntry*> order;
    for (const auto& e : lib.entries())
      if (e.root == 0 && indexed_files.count(e.relative_path)) order.push_back(&e);
    for (const auto& e : lib.entries())
      if (e.root == 0 && !indexed_files.count(e.relative_path)) order.push_back(&e);
    // Names first (they win over aliases when `like` looks a word up), then aliases.
    for (const auto* e : order) claim(e->name, *e, entry_loc(*e), false);
    for (const auto* e : order)
      for (const auto& st : e->syntax.statements)
        if (const auto* a = std::get_if<compiler::AliasStmt>(&st.node))
          if (a->name != e->name) claim(a->name, *e, a->location, true);
  }

  // E0609: `deprecated replaced-by` must name an existing entry that is not itself deprecated.
  void deprecations() {
    for (const auto& e : lib.entries())
      for (const auto& st : e.syntax.statements) {
        if (e.root != 0) break;
        const auto* x = std::get_if<compiler::DeprecatedStmt>(&st.node);
        if (!x) continue;
        const auto* target = lib.entry(x->replacement);
        if (!target) {
          const auto guess = compiler::closest_match(x->replacement, lib.names());
          out.error("E0609", at(x->location), "replacement " + quoted(x->replacement) + " is not an entry of the library",
                    guess.empty() ? "name the entry that replaces this one (`sandpaper library` lists them)"
                                  : "did you mean `" + guess + "`?");
        } else if (target->name == e.name) {
          out.error("E0609", at(x->location), "entry " + quoted(e.name) + " is deprecated in favour of itself",
                    "name the entry that replaces it, or remove the `deprecated` line");
        } else if (!target->deprecated_by.empty()) {
          auto& d = out.error("E0609", at(x->location),
                              "replacement " + quoted(target->name) + " is itself deprecated (replaced by " +
                                  quoted(target->deprecated_by) + ")",
                              "write deprecated replaced-by " + target->deprecated_by + ": point at an entry that is not deprecated");
          d.notes.push_back({entry_loc(*target), quoted(target->name) + " is deprecated here"});
        }
      }
  }

  // E0608: `like` cycles, each reported once with its whole path (aliases as written).
  std::set<std::string> cycles() {
    struct Edge {
      std::string to, as;
      SourceLocation loc;
    };
    std::map<std::string, std::vector<Edge>> graph;
    // Keyed by qualified name (world:corduroy when layered): a lab's corduroy may build on the world's.
    for (const auto& e : lib.entries()) {
      if (!owns_name(e)) continue;  // a duplicate name: E0607 already
      for (const auto& st : e.syntax.statements)
        if (const auto* l = std::get_if<compiler::LikeStmt>(&st.node))
          if (const auto* to = lib.entry(l->name)) graph[lib.qualified_name(e)].push_back({lib.qualified_name(*to), l->name, l->name_location});
    }
    std::set<std::string> in_cycle;
    std::set<std::vector<std::string>> reported;
    std::map<std::string, int> state;  // 0 new, 1 on stack, 2 done
    std::vector<std::pair<std::string, const Edge*>> stack;
    std::function<void(const std::string&)> visit = [&](const std::string& n) {
      state[n] = 1;
      for (const auto& edge : graph[n]) {
        stack.emplace_back(n, &edge);
        if (state[edge.to] == 1) {
          // The cycle: from where edge.to sits on the stack to here.
          std::size_t start = 0;
          while (stack[start].first != edge.to) ++start;
          std::vector<std::pair<std::string, const Edge*>> cyc(stack.begin() + static_cast<std::ptrdiff_t>(start), stack.end());
          auto smallest = std::min_element(cyc.begin(), cyc.end(), [](auto& a, auto& b) { return a.first < b.first; });
          std::rotate(cyc.begin(), smallest, cyc.end());
          std::vector<std::string> key;
          for (const auto& [from, _] : cyc) key.push_back(from), in_cycle.insert(from);
          if (reported.insert(key).second) report_cycle(cyc);
        } else if (state[edge.to] == 0) {
          visit(edge.to);
        }
        stack.pop_back();
      }
      state[n] = 2;
    };
    for (const auto& e : lib.entries())
      if (e.root == 0 && state[lib.qualified_name(e)] == 0) visit(lib.qualified_name(e));
    return in_cycle;
  }

  template <typename Cycle>
  void report_cycle(const Cycle& cyc) {
    std::string path = cyc.front().first;
    for (const auto& [from, edge] : cyc)
      path += " -> " + edge->to + (edge->as != edge->to ? " (as " + quoted(edge->as) + ")" : "");
    auto& d = out.error("E0608", at(cyc.front().second->loc), "`like` cycle: " + path,
                        cyc.size() == 1 ? "an entry must not start from itself: remove this `like`"
                                        : "an entry must not, through `like`, start from itself: remove one of the `like` "
                                          "lines on this path, or point it at an entry outside the cycle");
    for (std::size_t i = 1; i < cyc.size(); ++i)
      d.notes.push_back({at(cyc[i].second->loc), quoted(cyc[i].first) + " starts from " + quoted(cyc[i].second->to) + " here"});
  }
};

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
void accept_check_warnings(const compiler::Library& lib, const DisplayPaths& disp, const Checker& ck,
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
      auto& x = one.accepted(d.code, d.location, "accepted: " + d.message, d.suggestion);
      x.notes = d.notes;
      x.notes.push_back({ck.at(a->location), "accepted here: \"" + a->reason + "\""});
      result.accepted.append(one);
      accepted_by[it->second].insert(d.code);
      continue;
    }
    // (An E0009 / W0009 "too many" line is kept as it was: what it counts was not kept to move.)
    auto& x = d.severity == compiler::Severity::Error ? one.error(d.code, d.location, d.message, d.suggestion)
                                                      : one.warning(d.code, d.location, d.message, d.suggestion);
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
  const DisplayPaths disp(lib);
  auto& out = result.diagnostics;
  for (const auto& e : lib.entries()) result.entries += e.root == 0;
  Checker ck{lib, disp, out};
  ck.indexed_files = established ? *established : indexed_files(roots);

  // The manifest and the entries' syntax (E0601, the compiler's E01xx/E02xx): the front root's.
  {
    Diagnostics front;
    const std::string prefix = lib.layered() ? "library/" + lib.roots().front().id + "/" : "library/";
    for (const auto& d : lib.scan_diagnostics().all())
      if (!lib.layered() || (d.location.file && (d.location.file->name.rfind(prefix, 0) == 0 ||
                                                 d.location.file->name == "library/library.toml")))
        front.append([&] {
          Diagnostics one;
          auto& x = d.severity == compiler::Severity::Error ? one.error(d.code, d.location, d.message, d.suggestion)
                                                            : one.warning(d.code, d.location, d.message, d.suggestion);
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
      (w.severity == compiler::Severity::Note ? one.accepted(moved.code, moved.location, message, moved.suggestion)
                                              : one.warning(moved.code, moved.location, message, moved.suggestion))
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
  if (!root_found) throw std::invalid_argument("no root named '" + options.root + "' in the library path");
  for (std::size_t i = 0; i < roots.size(); ++i)
    if (options.root.empty() || whole.roots()[i].id == options.root)
      check_front_root(std::vector<std::filesystem::path>(roots.begin() + static_cast<std::ptrdiff_t>(i), roots.end()), cal_dir,
                       cal, result, progress, i == 0 ? options.established : std::nullopt);
  return result;
}

}  // namespace sandpaper::curation
