// Hierarchical clustering (6.3's analysis): merge heights by hand for single and average linkage,
// cutting the tree, and the dendrogram's leaf order.
#include <gtest/gtest.h>

#include "sandpaper/experiment/clustering.hpp"

namespace sandpaper::experiment {
namespace {

// Points on a line at 0, 1, 3, 7: single linkage joins {0,1} at 1, then 3 at 2, then 7 at 4;
// average linkage joins {0,1} at 1, then 3 at (3 + 2) / 2 = 2.5, then 7 at (7 + 6 + 4) / 3.
std::vector<std::vector<double>> line() {
  const double x[] = {0, 1, 3, 7};
  std::vector<std::vector<double>> d(4, std::vector<double>(4));
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) d[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = std::abs(x[i] - x[j]);
  return d;
}

TEST(Clustering, SingleLinkageHeights) {
  const auto m = cluster(line(), Linkage::Single);
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[0].a, 0);
  EXPECT_EQ(m[0].b, 1);
  EXPECT_DOUBLE_EQ(m[0].height, 1);
  EXPECT_EQ(m[1].a, 2);
  EXPECT_EQ(m[1].b, 4);
  EXPECT_DOUBLE_EQ(m[1].height, 2);
  EXPECT_DOUBLE_EQ(m[2].height, 4);
  EXPECT_EQ(m[2].size, 4);
}

TEST(Clustering, AverageLinkageHeights) {
  const auto m = cluster(line(), Linkage::Average);
  EXPECT_DOUBLE_EQ(m[0].height, 1);
  EXPECT_DOUBLE_EQ(m[1].height, 2.5);
  EXPECT_DOUBLE_EQ(m[2].height, 17.0 / 3.0);
}

TEST(Clustering, CutAndOrder) {
  const auto m = cluster(line(), Linkage::Single);
  EXPECT_EQ(cut_tree(m, 4, 2), (std::vector<int>{0, 0, 0, 1}));
  EXPECT_EQ(cut_tree(m, 4, 3), (std::vector<int>{0, 0, 1, 2}));
  EXPECT_EQ(cut_tree(m, 4, 1), (std::vector<int>{0, 0, 0, 0}));
  EXPECT_EQ(cut_tree(m, 4, 4), (std::vector<int>{0, 1, 2, 3}));
  // Each merge draws its smaller id first: the last merge is (leaf 3, cluster {2, {0, 1}}).
  EXPECT_EQ(leaf_order(m, 4), (std::vector<int>{3, 2, 0, 1}));
  EXPECT_THROW(cut_tree(m, 4, 0), std::invalid_argument);
}

TEST(Clustering, RefusesBadMatrices) {
  EXPECT_THROW(cluster({}, Linkage::Single), std::invalid_argument);
  EXPECT_THROW(cluster({{0, 1}, {2, 0}}, Linkage::Single), std::invalid_argument);
  EXPECT_THROW(cluster({{0, -1}, {-1, 0}}, Linkage::Single), std::invalid_argument);
  EXPECT_THROW(cluster({{0, 1}, {1}}, Linkage::Single), std::invalid_argument);
}

}  // namespace
}  // namespace sandpaper::experiment
