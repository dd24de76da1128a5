// The spatial index against a brute-force back-to-front scan (Appendix B: the frontmost patch
// under the cursor is the one that sends force), on seeded random workspaces.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "sandpaper/runtime/patch_grid.hpp"
#include "workspace_test_support.hpp"

namespace sandpaper::runtime {
namespace {

using testws::unit;

// The definition, restated: the last rectangle (in painting order) with |p - c| <= h on both axes.
std::uint32_t brute_force(const std::vector<PatchRect>& rects, glm::dvec2 p) {
  for (std::size_t i = rects.size(); i-- > 0;) {
    const auto& r = rects[i];
    if (std::abs(p.x - r.centre_m.x) <= r.half_m.x && std::abs(p.y - r.centre_m.y) <= r.half_m.y)
      return static_cast<std::uint32_t>(i);
  }
  return PatchGrid::kNoPatch;
}

TEST(PatchGrid, MatchesBruteForceOnRandomWorkspaces) {
  std::mt19937_64 rng(20240531);
  const glm::dvec2 half{0.1143, 0.1143};
  std::size_t checked = 0, on_some_patch = 0;
  for (int trial = 0; trial < 150; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const auto n = static_cast<std::size_t>(unit(rng) * (trial < 10 ? 3 : 300));
    std::vector<PatchRect> rects;
    for (std::size_t i = 0; i < n; ++i) {
      // Sizes log-uniform from 0.1 mm to 200 mm; some patches hang over the workspace edge.
      const double w = 1e-4 * std::pow(2000.0, unit(rng)), h = 1e-4 * std::pow(2000.0, unit(rng));
      rects.push_back({{(unit(rng) * 2.4 - 1.2) * half.x, (unit(rng) * 2.4 - 1.2) * half.y}, {0.5 * w, 0.5 * h}});
    }
    PatchGrid grid(rects, half);
    std::vector<glm::dvec2> points;
    for (int k = 0; k < 1500; ++k) points.push_back({(unit(rng) * 3 - 1.5) * half.x, (unit(rng) * 3 - 1.5) * half.y});
    // Edges and corners exactly, and a hair either side of them.
    for (const auto& r : rects)
      for (double sx : {-1.0, 0.0, 1.0})
        for (double sy : {-1.0, 1.0}) {
          const glm::dvec2 e = r.centre_m + glm::dvec2{sx * r.half_m.x, sy * r.half_m.y};
          points.push_back(e);
          points.push_back({std::nextafter(e.x, 1.0), std::nextafter(e.y, -1.0)});
          points.push_back({std::nextafter(e.x, -1.0), std::nextafter(e.y, 1.0)});
        }
    for (const auto& p : points) {
      const auto expected = brute_force(rects, p);
      ASSERT_EQ(grid.frontmost_at(p), expected) << "at (" << p.x << ", " << p.y << ") with " << n << " patches";
      ++checked;
      on_some_patch += expected != PatchGrid::kNoPatch;
    }
  }
  // The sample must exercise both answers, or the comparison proves little.
  EXPECT_GT(on_some_patch, checked / 5);
  EXPECT_LT(on_some_patch, checked);
}

TEST(PatchGrid, LaterRectanglesLieInFront) {
  const std::vector<PatchRect> rects{{{0, 0}, {0.02, 0.02}}, {{0.01, 0}, {0.02, 0.02}}, {{0.05, 0.05}, {0.001, 0.001}}};
  PatchGrid grid(rects, {0.1, 0.1});
  EXPECT_EQ(grid.frontmost_at({-0.015, 0}), 0u);  // only the first covers it
  EXPECT_EQ(grid.frontmost_at({0.005, 0}), 1u);   // both: the second is in front
  EXPECT_EQ(grid.frontmost_at({0.025, 0}), 1u);
  EXPECT_EQ(grid.frontmost_at({0.05, 0.05}), 2u);
  EXPECT_EQ(grid.frontmost_at({0.08, -0.08}), PatchGrid::kNoPatch);
}

TEST(PatchGrid, NoPatchesAndNonFinitePoints) {
  PatchGrid empty({}, {0.1, 0.1});
  EXPECT_EQ(empty.frontmost_at({0, 0}), PatchGrid::kNoPatch);
  const std::vector<PatchRect> one{{{0, 0}, {0.05, 0.05}}};
  PatchGrid grid(one, {0.1, 0.1});
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(grid.frontmost_at({nan, 0}), PatchGrid::kNoPatch);
  EXPECT_EQ(grid.frontmost_at({0, inf}), PatchGrid::kNoPatch);
  EXPECT_EQ(grid.frontmost_at({0, 0}), 0u);
}

TEST(PatchGrid, RefusesBadRectangles) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(PatchGrid(std::vector<PatchRect>{{{nan, 0}, {0.01, 0.01}}}, {0.1, 0.1}), std::invalid_argument);
  EXPECT_THROW(PatchGrid(std::vector<PatchRect>{{{0, 0}, {-0.01, 0.01}}}, {0.1, 0.1}), std::invalid_argument);
}

// The cost of a lookup is the length of one cell's list. A tiled workspace keeps it at a few
// patches whether it holds 1 or 1,024 patches (the timing itself is in bench/workspace_bench.cpp).
TEST(PatchGrid, CellListsStayShortAsPatchesMultiply) {
  for (int side : {1, 4, 32}) {
    std::vector<PatchRect> rects;
    const double cell = 0.2 / side;
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j)
        rects.push_back({{-0.1 + (i + 0.5) * cell, -0.1 + (j + 0.5) * cell}, {0.45 * cell, 0.45 * cell}});
    PatchGrid grid(rects, {0.1, 0.1});
    SCOPED_TRACE(std::to_string(rects.size()) + " patches");
    EXPECT_LE(grid.max_cell_entries(), 4u);
    EXPECT_LE(grid.entries(), 4 * rects.size());
  }
}

// Many big patches over each other must not make the index explode: it coarsens instead.
TEST(PatchGrid, OverlappingGiantsKeepTheIndexSmall) {
  std::vector<PatchRect> rects;
  for (int i = 0; i < 500; ++i) rects.push_back({{0, 0}, {0.1, 0.1}});
  for (int i = 0; i < 500; ++i) rects.push_back({{-0.09 + 0.00036 * i, 0.0}, {0.0001, 0.0001}});
  PatchGrid grid(rects, {0.1, 0.1});
  EXPECT_LE(grid.entries(), std::max<std::size_t>(1 << 16, 64 * rects.size()));
  EXPECT_EQ(grid.frontmost_at({0.05, 0.05}), 499u);
  EXPECT_EQ(grid.frontmost_at({-0.09, 0.0}), 500u);
}

}  // namespace
}  // namespace sandpaper::runtime
