// "Did you mean" suggestions (compiler/src/front/diagnostic.cpp): the edit distance, and closest_match,
// which skips candidates by length and stops a walk once it is over the best so far, checked against
// a plain full-table Levenshtein and the documented choice (the nearest within a third of the word's
// length, ties to the closest length, then the first listed).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"

namespace {

using sandpaper::compiler::closest_match;
using sandpaper::compiler::edit_distance;

std::size_t full_levenshtein(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> t(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) t[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) t[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j)
      t[i][j] = std::min({t[i - 1][j] + 1, t[i][j - 1] + 1, t[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0u : 1u)});
  return t[a.size()][b.size()];
}

std::size_t gap(const std::string& a, const std::string& b) {
  return a.size() > b.size() ? a.size() - b.size() : b.size() - a.size();
}

// Every candidate's full distance; the first of the nearest, among them the first of the closest length.
std::string reference_match(const std::string& word, const std::vector<std::string>& candidates) {
  const std::string* best = nullptr;
  std::size_t best_d = 0;
  for (const auto& c : candidates) {
    const std::size_t d = full_levenshtein(word, c);
    if (!best || d < best_d || (d == best_d && gap(word, c) < gap(word, *best))) {
      best = &c;
      best_d = d;
    }
  }
  const std::size_t limit = std::clamp<std::size_t>(word.size() / 3, 1, 3);
  if (!best || best_d == 0 || best_d > limit) return {};
  return *best;
}

std::string random_word(std::mt19937& rng, std::size_t max_len) {
  // Three letters, so that near words, ties and exact matches are common.
  std::uniform_int_distribution<std::size_t> len(0, max_len);
  std::uniform_int_distribution<int> letter(0, 2);
  std::string w(len(rng), 'a');
  for (auto& ch : w) ch = static_cast<char>('a' + letter(rng));
  return w;
}

TEST(Suggestion, EditDistanceOfKnownPairs) {
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("abc", ""), 3u);
  EXPECT_EQ(edit_distance("N/mn", "N/mm"), 1u);
  EXPECT_EQ(edit_distance("roughness", "roughness"), 0u);
  EXPECT_EQ(edit_distance("flaw", "lawn"), 2u);
}

TEST(Suggestion, TypoIsMatchedTiesGoToTheClosestLengthAndExactOrFarGiveNothing) {
  EXPECT_EQ(closest_match("N/mn", {"N/m", "N/mm"}), "N/mm");
  EXPECT_EQ(closest_match("corduroi", {"velvet", "corduroy", "sandpaper-80"}), "corduroy");
  EXPECT_EQ(closest_match("corduroy", {"corduroy", "cordurox"}), "");  // already a name: nothing to suggest
  EXPECT_EQ(closest_match("glass", {"sandpaper-80", "corduroy"}), "");
  EXPECT_EQ(closest_match("abc", {}), "");
}

TEST(Suggestion, ClosestMatchAgreesWithTheFullTableOnRandomLists) {
  std::mt19937 rng(20261125);
  std::uniform_int_distribution<std::size_t> count(0, 12);
  for (int trial = 0; trial < 20000; ++trial) {
    const std::string word = random_word(rng, 10);
    std::vector<std::string> candidates(count(rng));
    for (auto& c : candidates) c = random_word(rng, 12);
    for (const auto& c : candidates) ASSERT_EQ(edit_distance(word, c), full_levenshtein(word, c)) << word << " / " << c;
    ASSERT_EQ(closest_match(word, candidates), reference_match(word, candidates)) << "word " << word << ", trial " << trial;
  }
}

}  // namespace
