#pragma once
// The catalog index's data files as text (index_page.cpp writes them, index_patch.cpp rewrites the
// parts a change touches): the head with the families and each part's span, and the parts, one
// column a key. Internal to the catalog library.
#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "sandpaper/catalog/index_page.hpp"

namespace sandpaper::catalog::index_parts {

struct FamilyCount {
  std::string id, title, describes;
  int count = 0;
  bool stimulus = false;  // a published stimulus set (library.toml `stimulus-set`): ranked after the materials
};

// The data files' statements around their JSON (json_statement, html.hpp).
inline constexpr std::string_view kHeadStart = "window.sandpaperCatalog = JSON.parse('", kHeadEnd = "');\n";
inline constexpr std::string_view kPartStart =
    "(window.sandpaperCatalogParts = window.sandpaperCatalogParts || []).push(JSON.parse('";
inline constexpr std::string_view kPartEnd = "'));\n";

// A string as its JSON text (non-ASCII kept, invalid UTF-8 replaced).
std::string json_string(const std::string& s);
// The JSON inside a file json_statement wrote (its escapes \\ and \' undone), or nullopt.
std::optional<std::string> json_inside(const std::string& script, std::string_view start, std::string_view end);
// A roughness to six significant digits as JSON ("null" when there is none).
std::string roughness_text(const std::optional<double>& r);
// Forces and periods to the same six digits.
std::string six_digits(double v);

// One part's columns, each value as its JSON text; aliases, deprecated_by, root and no_thumbnail by row in the part.
struct PartColumns {
  std::vector<std::string> name, family, roughness, describes, licence, sources, force, period, kind;
  std::map<std::size_t, std::string> aliases, deprecated_by, root;
  std::set<std::size_t> no_thumbnail;

  // Sets row i (which must exist) from r; family_index holds the families' indices by id.
  void set(std::size_t i, const IndexRow& r, const std::map<std::string, int>& family_index) {
    if (r.page != "entries/" + r.name + ".html")
      throw std::invalid_argument("index_files: " + r.name + "'s page is not entries/" + r.name + ".html");
    if (!r.thumbnail.empty() && r.thumbnail != "entries/" + r.name + "-thumb.png")
      throw std::invalid_argument("index_files: " + r.name + "'s thumbnail is not entries/" + r.name + "-thumb.png");
    name[i] = json_string(r.name);
    family[i] = std::to_string(r.family.empty() ? -1 : family_index.at(r.family));
    roughness[i] = roughness_text(r.roughness);
    describes[i] = json_string(r.describes);
    licence[i] = json_string(r.licence);
    sources[i] = std::to_string(r.source_kinds);
    force[i] = six_digits(r.max_lateral_force_N);
    period[i] = six_digits(r.period_m);
    kind[i] = json_string(r.kind);
    if (r.root.empty()) root.erase(i);
    else root[i] = json_string(r.root);
    if (r.aliases.empty()) aliases.erase(i);
    else aliases[i] = nlohmann::json(r.aliases).dump(-1, ' ', true);
    if (r.deprecated_by.empty()) deprecated_by.erase(i);
    else deprecated_by[i] = json_string(r.deprecated_by);
    if (r.thumbnail.empty()) no_thumbnail.insert(i);
    else no_thumbnail.erase(i);
  }
  void resize(std::size_t n) {
    for (auto* c : {&name, &family, &roughness, &describes, &licence, &sources, &force, &period, &kind}) c->resize(n);
  }
};

// A part as the head describes it: its first and last names, its rows, and how many of them are in
// each family and in none. The head's totals are the sums over its parts, and a patch recounts the
// parts it rewrites from their rows, so that a run cut off between writing a part and writing the
// head is put right by the next run, which patches the same rows again.
struct PartSpan {
  std::string first, last;
  std::size_t rows = 0;
  std::vector<int> counts;  // by family index
  std::size_t unfiled = 0;
};

// What the head file holds: all the page needs, and where each part's names start and end.
struct Head {
  std::string library_name, version;
  std::vector<FamilyCount> families;
  std::size_t entries = 0, unfiled = 0;
  bool sorted = true;
  std::vector<PartSpan> parts;
};

// Counts c's rows into span's counts (over `families` families); std::invalid_argument for a family
// index outside them.
void tally(const PartColumns& c, std::size_t families, PartSpan& span);
// The head's family counts and unfiled entries: the sums over its parts.
void total(Head& h);
std::string head_script(const Head& h);
std::string part_script(std::size_t k, const PartColumns& c);
std::string page_of(const Head& h);
// Each family's index in the list, by id.
std::map<std::string, int> index_of(const std::vector<FamilyCount>& families);

}  // namespace sandpaper::catalog::index_parts
