// `sandpaper library search|show|near`: the queries, answered from the indexes (docs/LIBRARY.md).
#include "cmd_library_shared.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/schema/json_text.hpp"
#include "sandpaper/schema/patch_json.hpp"
#include "sandpaper/compiler/display_paths.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/layers.hpp"
#include "sandpaper/curation/near.hpp"
#include "sandpaper/curation/search.hpp"

namespace sandpaper::cli::library_cmd {

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
  const compiler::DisplayPaths shown(p.roots[layer]);
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
  const compiler::DisplayPaths every_root(ids);
  // As explain shows them (95 mm, 0 deg), not in raw SI: the JSON keeps value_si and si_unit.
  const auto value_of = [](const cur::IndexedProvenance& r) {
    return r.si_unit.empty() ? r.stated : schema::display_value(r.value_si, r.si_unit);
  };
  // Each column as wide as its widest cell ("representative" is a layer too), so the columns line up.
  std::size_t wp = 0, wv = 0, wl = 0;
  for (const auto& r : prov)
    wp = std::max(wp, r.parameter.size()), wv = std::max(wv, value_of(r).size()), wl = std::max(wl, r.layer.size());
  for (const auto& r : prov) {
    std::cout << "  " << pad(r.parameter, wp) << "  " << pad(value_of(r), wv) << "  " << pad(r.layer, wl) << "  "
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
  const cur::WeberFractions w = idx.weber_fractions();
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
                         {"from", from}, {"weber_fraction", idx.weber_fraction()},
                         {"weber_fractions", {{"force", w.force}, {"stiffness", w.stiffness}, {"damping", w.damping}, {"friction", w.friction}}},
                         {"nearest", arr}},
                     2)
              << "\n";
    return kExitOk;
  }
  std::cout << "nearest to " << from << " (distance in JND steps: force " << num(w.force * 100) << " %, stiffness "
            << num(w.stiffness * 100) << " %, damping " << num(w.damping * 100) << " %, friction coefficient "
            << num(w.friction * 100) << " %; a period doubling counts " << num(cur::kJndPerPeriodDoubling)
            << ", docs/LIBRARY.md)\n";
  std::size_t wn = 0;
  for (const auto& n : ns) wn = std::max(wn, shown_name(n.entry, p.layered()).size());
  for (const auto& n : ns)
    std::cout << "  " << std::setw(6) << std::fixed << std::setprecision(1) << n.distance << std::defaultfloat << "  "
              << pad(shown_name(n.entry, p.layered()), wn) << "  " << n.why << "\n";
  return kExitOk;
}

}  // namespace sandpaper::cli::library_cmd
