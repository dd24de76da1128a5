#pragma once
// `sandpaper library search`: entries by name, alias, words (word_rank.hpp, the catalog's rule too) and roughness range, from the index.
#include <optional>
#include <string>
#include <vector>

#include "sandpaper/curation/index.hpp"

namespace sandpaper::curation {

// A closed, half-open or open roughness range: "0.4..0.6", "0.4..", "..0.6" (ratio scale, inclusive).
// A stored roughness is what the map's round trip gives back for the value written (`roughness
// 0.22` is held as 0.21999999999999997), so the bounds take in values within kRoughnessTolerance of
// them: the value written is in, and no two values a file can write (6 significant digits) are merged.
// A roughness is also in when the value shown for it (3 significant digits, schema::roughness_text,
// as the catalog's page shows it) is: an entry shown as 0.0982 (stored 0.09822) is in ..0.0982.
struct RoughnessRange {
  static constexpr double kRoughnessTolerance = 1e-9;
  std::optional<double> min, max;
  bool contains(double r) const;
};
// Throws std::invalid_argument with a message that gives the form, for anything else.
RoughnessRange parse_roughness_range(const std::string& text);

struct SearchQuery {
  std::vector<std::string> words;
  std::optional<RoughnessRange> roughness;
  std::string family;   // empty: any
  std::size_t limit = 20;
};

struct SearchHit {
  IndexedEntry entry;
  std::string matched_alias;  // the alias the query named, if it matched by alias
  std::string why;            // "name", "alias", "words", "all" (no words: every entry in range)
  double rank = 0;            // -word_score for word matches (lower is better); -roughness after "rough", roughness after "smooth"
  bool stimulus = false;      // of a published stimulus set's family (Index::stimulus_families), the query naming no family
};

// The order of hits: exact names, exact aliases, word matches by rank (or, without words, every
// entry by roughness), then a stimulus set's entries by rank. Ties keep their order.
bool search_before(const SearchHit& a, const SearchHit& b);

// Ranked: an exact name first, then an exact alias, then the entries every word matches, by
// word_score (word_rank.hpp: a word begins a word of a field; name 8, alias 4, describes 2, family 1),
// equal scores by name; filtered by family and roughness. Without words: every entry in range, by roughness. The words rough, rougher,
// roughest, coarse, coarser, coarsest (smooth, smoother, smoothest) are not matched as text unless
// an entry is so named: they keep the textured entries at or above (below) the library's median
// roughness and order the matches roughest (smoothest) first. A stimulus set's entries come after
// the materials unless `family` names theirs. Throws std::invalid_argument for a family the index
// does not have (with "did you mean").
std::vector<SearchHit> search(const Index& index, const SearchQuery& q);

// The FTS5 query for `words`: each word quoted, the last one also as a prefix ("corduroy" "wal"*).
std::string fts_query(const std::vector<std::string>& words);

}  // namespace sandpaper::curation
