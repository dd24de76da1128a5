// The word ranking shared with the catalog's page (word_rank.hpp).
#include "sandpaper/curation/word_rank.hpp"

#include <algorithm>

namespace sandpaper::curation {

std::vector<std::string> search_tokens(std::string_view text) {
  std::vector<std::string> out;
  std::string word;
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c >= 0x80) word += ch;
    else if (c >= 'A' && c <= 'Z') word += static_cast<char>(c - 'A' + 'a');
    else if (!word.empty()) out.push_back(std::move(word)), word.clear();
  }
  if (!word.empty()) out.push_back(std::move(word));
  return out;
}

namespace {

bool begins_a_word(const std::string& query_word, std::string_view text) {
  for (const auto& w : search_tokens(text))
    if (w.compare(0, query_word.size(), query_word) == 0) return true;
  return false;
}

}  // namespace

int word_score(const std::vector<std::string>& query_words, const WordFields& f) {
  if (query_words.empty()) return 0;
  int score = 0;
  for (const auto& q : query_words) {
    int best = 0;
    if (begins_a_word(q, f.name)) best = kNameWord;
    else if (std::any_of(f.aliases.begin(), f.aliases.end(), [&](const auto& a) { return begins_a_word(q, a); })) best = kAliasWord;
    else if (begins_a_word(q, f.describes)) best = kDescribesWord;
    else if (begins_a_word(q, f.family) || begins_a_word(q, f.family_title)) best = kFamilyWord;
    if (best == 0) return 0;
    score += best;
  }
  return score;
}

}  // namespace sandpaper::curation
