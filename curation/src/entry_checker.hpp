#pragma once
// `library check`'s checks of one library (check.cpp runs them): each entry's metadata, licences,
// sources and images, then names, deprecations and `like` cycles across the entries. Each check names
// its code; docs/LIBRARY.md, "What check checks", lists them. Internal to the curation library.
#include <algorithm>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/display_paths.hpp"
#include "sandpaper/curation/licences.hpp"
#include "sandpaper/schema/confined_path.hpp"

namespace sandpaper::curation::check_detail {

using compiler::Diagnostic;
using compiler::Diagnostics;
using compiler::LibraryEntry;
using compiler::SourceLocation;

inline std::string quoted(const std::string& s) { return "'" + s + "'"; }

inline std::string fmt(double v, int digits = 3) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

struct Checker {
  const compiler::Library& lib;
  const compiler::DisplayPaths& disp;
  Diagnostics& out;
  // The front root's files that its index (if it has one, of this folder) lists as owning their
  // names: in a clash of names these are the established entries, and the other file is the newcomer.
  std::set<std::string> indexed_files = {};
  // When set: of the files in a clash of names (relative to the front root), the rank of the first
  // commit that added each, oldest 0 (first_added.hpp); a file git knows came before one it does not.
  std::function<std::map<std::string, std::size_t>(const std::vector<std::string>&)> history = nullptr;
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
      out.error("E0615", top, "the licence file of image " + quoted(h.path) + " has no SPDX-License-Identifier", "add a line:\n" + form.substr(0, form.find('\n')));
    if (side->credit.empty())
      out.error("E0615", top, "the licence file of image " + quoted(h.path) + " has no SPDX-FileCopyrightText (the credit)",
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
      const bool named_inside = !(p.is_absolute() || inside.empty() || *inside.begin() == "..");
      if (!named_inside) {
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
      // A link that leads out is named inside: its licence file belongs beside it there, whether or
      // not the image is copied in, so both are said in one round.
      if (named_inside) image_licence(e, *h, inside);
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
    // Which file came first, for the files in a clash: git's history, when it knows.
    std::map<std::string, std::size_t> added;
    if (history) {
      std::map<std::string, std::set<const LibraryEntry*>> claimants;
      for (const auto& e : lib.entries()) {
        if (e.root != 0) continue;
        claimants[e.name].insert(&e);
        for (const auto& a : e.aliases) claimants[a].insert(&e);
      }
      std::set<std::string> contested;
      for (const auto& [token, es] : claimants)
        if (es.size() > 1)
          for (const auto* e : es) contested.insert(e->relative_path);
      if (!contested.empty()) added = history({contested.begin(), contested.end()});
    }
    const auto rank = [&](const LibraryEntry& e) {
      const auto it = added.find(e.relative_path);
      return it == added.end() ? std::numeric_limits<std::size_t>::max() : it->second;
    };
    std::map<std::string, First> seen;
    auto claim = [&](const std::string& token, const LibraryEntry& e, const SourceLocation& loc, bool alias) {
      auto [it, fresh] = seen.emplace(token, First{&e, loc, alias});
      if (fresh || it->second.entry == &e) return;
      const auto& f = it->second;
      const std::string first_as = f.alias ? "an alias of " + quoted(f.entry->name) : "the name of " + f.entry->relative_path;
      const bool by_git = rank(*f.entry) < rank(e);
      const bool indexed = !by_git && indexed_files.count(f.entry->relative_path) > 0;
      const auto free = free_name(token);
      const auto dir = std::filesystem::path(e.relative_path).parent_path().string();
      auto& d = out.error("E0607", at(loc),
                          std::string(alias ? "alias " : "name ") + quoted(token) + " is already " + first_as +
                              (by_git ? " (committed to git before this file)" : indexed ? " (in the library's index)" : ""),
                          alias ? "names and aliases are unique across the whole library: remove this alias, or say one that is free (" +
                                      quoted(free) + " is)"
                                : "names are unique across the whole library (not per family): rename this file and its material "
                                  "to a free name that says how it differs, for instance " +
                                      (dir.empty() ? "" : dir + "/") + free + ".hmat with material \"" + free + "\"");
      d.notes.push_back({at(f.loc), f.alias ? "the alias of " + quoted(f.entry->name) : "the other entry named " + quoted(token)});
    };
    // The established entries claim first: those git committed first (in the order of their first
    // commits), then those the index has, then the others, each in path order: the error lands on the
    // newcomer, the file a reviewer is looking at.
    std::vector<const LibraryEntry*> order;
    for (const auto& e : lib.entries())
      if (e.root == 0) order.push_back(&e);
    std::stable_sort(order.begin(), order.end(), [&](const LibraryEntry* a, const LibraryEntry* b) {
      return std::make_pair(rank(*a), indexed_files.count(a->relative_path) == 0) <
             std::make_pair(rank(*b), indexed_files.count(b->relative_path) == 0);
    });
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

}  // namespace sandpaper::curation::check_detail
