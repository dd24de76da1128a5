#include "sandpaper/curation/search.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>
#include <stdexcept>

#include "sandpaper/compiler/diagnostic.hpp"

namespace sandpaper::curation {

namespace {

std::optional<double> parse_bound(const std::string& text, const std::string& whole) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !(v >= 0))
    throw std::invalid_argument("bad roughness range '" + whole + "': '" + text +
                                "' is not a roughness (a number >= 0); write A..B, A.. or ..B, e.g. 0.4..0.6");
  return v;
}

}  // namespace

RoughnessRange parse_roughness_range(const std::string& text) {
  const auto dots = text.find("..");
  if (dots == std::string::npos || text.find("..", dots + 2) != std::string::npos || text == "..")
    throw std::invalid_argument("bad roughness range '" + text + "': write A..B, A.. or ..B (ratio-scale roughness, e.g. 0.4..0.6)");
  RoughnessRange r{parse_bound(text.substr(0, dots), text), parse_bound(text.substr(dots + 2), text)};
  if (r.min && r.max && *r.min > *r.max)
    throw std::invalid_argument("bad roughness range '" + text + "': the low end is above the high end; write A..B with A <= B");
  return r;
}

std::string fts_query(const std::vector<std::string>& words) {
  std::string q;
  for (std::size_t i = 0; i < words.size(); ++i) {
    std::string w;
    for (char ch : words[i]) w += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    if (w.empty()) continue;
    if (!q.empty()) q += ' ';
    q += '"' + w + '"';
    if (i + 1 == words.size()) q += '*';  // the last word may still be being typed
  }
  return q;
}

std::vector<SearchHit> search(const Index& index, const SearchQuery& q) {
  if (!q.family.empty()) {
    const auto fams = index.families();
    if (std::find(fams.begin(), fams.end(), q.family) == fams.end()) {
      const auto guess = compiler::closest_match(q.family, fams);
      std::string all;
      for (const auto& f : fams) all += (all.empty() ? "" : ", ") + f;
      throw std::invalid_argument("no family '" + q.family + "' in the library; " +
                                  (guess.empty() ? "families: " + all : "did you mean '" + guess + "'?"));
    }
  }
  std::vector<SearchHit> hits;
  std::set<std::string> seen;
  // An entry without a texture has no roughness (the map does not apply): a roughness range leaves
  // it out, as the catalog's page does.
  auto keep = [&](const IndexedEntry& e) {
    return (q.family.empty() || e.family == q.family) &&
           (!q.roughness || (e.max_lateral_force_N > 0 && q.roughness->contains(e.roughness)));
  };
  auto add = [&](const std::string& name, const std::string& why, const std::string& alias, double rank) {
    if (seen.count(name)) return;
    auto e = index.entry(name);
    if (!e || !keep(*e)) return;
    seen.insert(name);
    hits.push_back({std::move(*e), alias, why, rank});
  };
  if (q.words.empty()) {
    auto all = index.entries();
    std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.roughness < b.roughness; });
    for (auto& e : all) add(e.name, "all", "", 0);
  } else {
    // Exact names, then exact aliases: of the whole query joined by '-' or spaces, and of each word.
    std::vector<std::string> candidates;
    std::string dashed, spaced;
    for (const auto& w : q.words) {
      dashed += (dashed.empty() ? "" : "-") + w;
      spaced += (spaced.empty() ? "" : " ") + w;
    }
    candidates.push_back(spaced);
    candidates.push_back(dashed);
    for (const auto& w : q.words) candidates.push_back(w);
    for (const auto& c : candidates)
      if (index.entry(c)) add(c, "name", "", 0);
    for (const auto& c : candidates)
      if (auto name = index.resolve(c); name && *name != c) add(*name, "alias", c, 0);
    for (const auto& [name, rank] : index.full_text(fts_query(q.words))) add(name, "words", "", rank);
  }
  if (hits.size() > q.limit) hits.resize(q.limit);
  return hits;
}

}  // namespace sandpaper::curation
