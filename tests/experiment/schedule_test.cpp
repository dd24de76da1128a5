// The trial order: fixed by design and subject (so resume rebuilds it), different between
// subjects, each repetition a full shuffled run through the set, practice first.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "sandpaper/experiment/schedule.hpp"

namespace sandpaper::experiment {
namespace {

const std::filesystem::path kExamples = std::filesystem::path(SANDPAPER_SOURCE_DIR) / "examples/experiments";

std::vector<std::vector<int>> orders(const std::vector<Trial>& s) {
  std::vector<std::vector<int>> out;
  for (const auto& t : s) out.push_back(t.stimuli);
  return out;
}

TEST(Schedule, SameSubjectSameOrderOtherSubjectOther) {
  const auto d = load_design(kExamples / "roughness-magnitude.toml");
  const auto a = make_schedule(d, "S01");
  EXPECT_EQ(orders(a), orders(make_schedule(d, "S01")));
  EXPECT_NE(orders(a), orders(make_schedule(d, "S02")));
  ASSERT_EQ(a.size(), 4u + 3u * 12u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].index, static_cast<int>(i));
    EXPECT_EQ(a[i].practice, i < 4);
  }
  // Each repetition presents every stimulus once.
  for (int r = 0; r < 3; ++r) {
    std::multiset<int> seen;
    for (const auto& t : a)
      if (!t.practice && t.repetition == r) seen.insert(t.stimuli.at(0));
    EXPECT_EQ(seen.size(), 12u);
    EXPECT_EQ(std::set<int>(seen.begin(), seen.end()).size(), 12u) << "repetition " << r;
  }
  // And the runs are not all in one order.
  std::vector<int> run0, run1;
  for (const auto& t : a)
    if (!t.practice) (t.repetition == 0 ? run0 : t.repetition == 1 ? run1 : run1).push_back(t.stimuli.at(0));
  run1.resize(12);
  EXPECT_NE(run0, run1);
}

TEST(Schedule, SortingNumbersThePatchesAfreshForEachSort) {
  const auto d = load_design(kExamples / "roughness-sorting.toml");
  const auto s = make_schedule(d, "S01");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].piles, 2);
  EXPECT_EQ(s[1].piles, 3);
  EXPECT_EQ(s[2].piles, 4);
  for (const auto& t : s) {
    auto sorted = t.stimuli;
    std::sort(sorted.begin(), sorted.end());
    std::vector<int> all(12);
    for (int i = 0; i < 12; ++i) all[static_cast<std::size_t>(i)] = i;
    EXPECT_EQ(sorted, all);
  }
  EXPECT_NE(s[0].stimuli, s[1].stimuli);
}

TEST(Schedule, TwoIntervalPlacesTheComparisonInBothIntervals) {
  const auto d = load_design(kExamples / "force-jnd.toml");
  const auto s = make_schedule(d, "S01");
  ASSERT_EQ(s.size(), 3u + 20u * 7u);
  int first = 0, second = 0;
  std::set<double> increments;
  for (const auto& t : s) {
    (t.comparison_interval == 1 ? first : second)++;
    EXPECT_TRUE(t.comparison_interval == 1 || t.comparison_interval == 2);
    increments.insert(t.increment);
  }
  EXPECT_EQ(increments.size(), 7u);
  EXPECT_GT(first, 40);
  EXPECT_GT(second, 40);
}

}  // namespace
}  // namespace sandpaper::experiment
