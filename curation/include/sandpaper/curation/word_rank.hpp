#pragma once
// The word ranking shared by `library search` and the catalog's index page (its assets/index.js
// implements the same rule; docs/LIBRARY.md, "search", states it and tests/curation/data/
// search_ranking.json is run against both).
#include <string>
#include <string_view>
#include <vector>

namespace sandpaper::curation {

// The words of a text: maximal runs of ASCII letters and digits and of non-ASCII bytes (UTF-8 letters
// stay whole), ASCII letters lower-cased. "Pinwale-corduroy (narrow)" -> pinwale, corduroy, narrow.
std::vector<std::string> search_tokens(std::string_view text);

// What a query's words are matched in: one entry's name, aliases, describes, family id and title.
struct WordFields {
  std::string name;
  std::vector<std::string> aliases;
  std::string describes, family, family_title;
};

// Points a field gives a query word that begins one of its words: name 8, alias 4, describes 2,
// family (id or title) 1; a word counts its best field only.
inline constexpr int kNameWord = 8, kAliasWord = 4, kDescribesWord = 2, kFamilyWord = 1;

// The entry's score for the query's words (search_tokens of the query): the sum over the words of the
// best field each begins a word of; 0 if any word begins none (every word must match). Higher ranks
// first; equal scores keep the library's order (by name).
int word_score(const std::vector<std::string>& query_words, const WordFields& fields);

}  // namespace sandpaper::curation
