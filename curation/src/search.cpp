#include "sandpaper/curation/search.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <map>
#include <set>
#include <stdexcept>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/curation/word_rank.hpp"
#include "sandpaper/schema/patch_json.hpp"

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

bool RoughnessRange::contains(double r) const {
  const auto within = [this](double v) {
    return (!min || v >= *min - kRoughnessTolerance) && (!max || v <= *max + kRoughnessTolerance);
  };
  return within(r) || within(std::strtod(schema::roughness_text(r).c_str(), nullptr));
}

bool search_before(const SearchHit& a, const SearchHit& b) {
  const auto category = [](const SearchHit& h) { return h.why == "name" ? 0 : h.why == "alias" ? 1 : h.stimulus ? 3 : 2; };
  const auto order = [](const SearchHit& h) { return h.why == "all" ? h.entry.roughness : h.rank; };
  if (category(a) != category(b)) return category(a) < category(b);
  return order(a) < order(b);
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

namespace {

// +1 for a word that asks for rough entries, -1 for smooth ones, 0 for any other.
int roughness_word(const std::string& w) {
  for (const char* r : {"rough", "rougher", "roughest", "coarse", "coarser", "coarsest"})
    if (w == r) return 1;
  for (const char* s : {"smooth", "smoother", "smoothest"})
    if (w == s) return -1;
  return 0;
}

}  // namespace

std::vector<SearchHit> search(const Index& index, const SearchQuery& query) {
  // Words about roughness keep the rougher (or smoother) half and order by roughness; the rest are matched.
  SearchQuery q = query;
  int feel = 0;
  q.words.clear();
  for (const auto& w : query.words) {
    std::string lower;
    for (const char c : w) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (const int r = roughness_word(lower); r != 0 && index.entry(lower) == std::nullopt && !index.resolve(lower)) feel = r;
    else q.words.push_back(w);
  }
  std::optional<double> median;
  if (feel != 0) {
    std::vector<double> rs;
    for (const auto& e : index.entries())
      if (e.max_lateral_force_N > 0) rs.push_back(e.roughness);
    if (!rs.empty()) {
      std::nth_element(rs.begin(), rs.begin() + static_cast<std::ptrdiff_t>(rs.size() / 2), rs.end());
      median = rs[rs.size() / 2];
    }
  }
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
           (!q.roughness || (e.max_lateral_force_N > 0 && q.roughness->contains(e.roughness))) &&
           (feel == 0 || (median && e.max_lateral_force_N > 0 && (feel > 0 ? e.roughness >= *median : e.roughness <= *median)));
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
    // Every word begins a word of the entry's fields: ranked by word_score (word_rank.hpp), the
    // catalog's rule too; equal scores in name order (the candidates come so).
    std::vector<std::string> words;
    for (const auto& w : q.words)
      for (auto& t : search_tokens(w)) words.push_back(std::move(t));
    if (!words.empty())
      for (const auto& f : index.word_candidates(words))
        if (const int score = word_score(words, f); score > 0) add(f.name, "words", "", -score);
  }
  // A rough or smooth query: the matches by roughness, roughest (smoothest) first, ranked so.
  if (feel != 0)
    for (auto& h : hits)
      if (h.why == "words" || h.why == "all") {
        h.why = "words";
        h.rank = -feel * h.entry.roughness;
      }
  // A published stimulus set's entries (the thesis' gratings) after the materials, unless the
  // query asks for that family: exact names and aliases stay first.
  if (q.family.empty()) {
    const auto stimuli = index.stimulus_families();
    for (auto& h : hits) h.stimulus = std::find(stimuli.begin(), stimuli.end(), h.entry.family) != stimuli.end();
  }
  std::stable_sort(hits.begin(), hits.end(), [](const SearchHit& a, const SearchHit& b) { return search_before(a, b); });
  if (hits.size() > q.limit) hits.resize(q.limit);
  return hits;
}

}  // namespace sandpaper::curation
