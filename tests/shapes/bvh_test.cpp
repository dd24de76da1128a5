// The BVH's segment query against a brute-force scan of every triangle (the same inline test), on
// 10,000 random segments with a fixed seed; and its cost against the triangle count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/primitives.hpp"

namespace sandpaper::shapes {
namespace {

std::optional<SegmentHit> brute_force(const Mesh& mesh, const glm::dvec3& a, const glm::dvec3& b,
                                      const std::vector<std::uint32_t>& excluded, Facing facing) {
  std::optional<SegmentHit> best;
  for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    if (std::find(excluded.begin(), excluded.end(), t) != excluded.end()) continue;
    const TriangleFrame& f = mesh.frame(t);
    const double s = segment_triangle_t(a, b - a, mesh.vertex0(t), f.e1, f.e2, facing);
    if (s >= 0.0 && (!best || s < best->t)) best = SegmentHit{s, a + s * (b - a), t};
  }
  return best;
}

// A soup of random, overlapping triangles in a 10 cm cube: no structure for the tree to exploit.
Mesh random_soup(std::mt19937_64& rng, std::size_t n) {
  std::uniform_real_distribution<double> coord(-0.05, 0.05);
  std::uniform_real_distribution<double> small(-0.01, 0.01);
  MeshData data;
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 c{coord(rng), coord(rng), coord(rng)};
    const auto base = static_cast<std::uint32_t>(data.vertices.size());
    for (int k = 0; k < 3; ++k) data.vertices.push_back(c + glm::dvec3{small(rng), small(rng), small(rng)});
    data.triangles.push_back({base, base + 1, base + 2});
  }
  return Mesh::build_nonrt(std::move(data));
}

void compare_on_random_segments(const Mesh& mesh, std::mt19937_64& rng, int count, Facing facing, int& hits) {
  const Bvh bvh = Bvh::build_nonrt(mesh);
  std::uniform_real_distribution<double> coord(-0.07, 0.07);
  for (int i = 0; i < count; ++i) {
    const glm::dvec3 a{coord(rng), coord(rng), coord(rng)};
    const glm::dvec3 b{coord(rng), coord(rng), coord(rng)};
    const auto expected = brute_force(mesh, a, b, {}, facing);
    const auto got = bvh.first_hit_rt(a, b, {}, facing);
    ASSERT_EQ(got.has_value(), expected.has_value()) << "segment " << i;
    if (!got) continue;
    ++hits;
    ASSERT_EQ(got->triangle, expected->triangle) << "segment " << i;
    ASSERT_NEAR(got->t, expected->t, 1e-12) << "segment " << i;
    // Skipping the first and second triangles found gives the next ones, as the scan does.
    std::vector<std::uint32_t> skip{got->triangle};
    for (int k = 0; k < 2; ++k) {
      const auto next_expected = brute_force(mesh, a, b, skip, facing);
      const auto next = bvh.first_hit_rt(a, b, skip, facing);
      ASSERT_EQ(next.has_value(), next_expected.has_value()) << "segment " << i << " skipping " << k + 1;
      if (!next) break;
      ASSERT_EQ(next->triangle, next_expected->triangle);
      ASSERT_NEAR(next->t, next_expected->t, 1e-12);
      skip.push_back(next->triangle);
    }
  }
}

TEST(Bvh, AgreesWithBruteForceOnASphere) {
  std::mt19937_64 rng(74);
  const Mesh sphere = uv_sphere(0.05, 96, 48);
  int hits = 0;
  compare_on_random_segments(sphere, rng, 5000, Facing::both, hits);
  compare_on_random_segments(sphere, rng, 5000, Facing::front_only, hits);
  EXPECT_GT(hits, 5000);  // most random segments through the cube cross the sphere
}

TEST(Bvh, AgreesWithBruteForceOnATriangleSoup) {
  std::mt19937_64 rng(1995);
  const Mesh soup = random_soup(rng, 3000);
  int hits = 0;
  compare_on_random_segments(soup, rng, 5000, Facing::both, hits);
  compare_on_random_segments(soup, rng, 5000, Facing::front_only, hits);
  EXPECT_GT(hits, 3000);
}

TEST(Bvh, ASegmentThroughASharedEdgeOrVertexHitsOneOfItsTriangles) {
  // The cube's edges and corners, and the sphere's pole, met exactly.
  const Mesh cube = box(glm::dvec3{0.0}, glm::dvec3{0.02});
  const Bvh cube_tree = Bvh::build_nonrt(cube);
  for (const glm::dvec3 target : {glm::dvec3{0.02, 0.0, 0.02}, glm::dvec3{0.02, 0.02, 0.02}, glm::dvec3{0.0, 0.0, 0.02},
                                  glm::dvec3{0.02, -0.02, 0.0}}) {
    const auto hit = cube_tree.first_hit_rt(target * 2.0, glm::dvec3{0.0}, {}, Facing::front_only);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->t, 0.5, 1e-12);
  }
  const Mesh sphere = uv_sphere(0.05, 64, 32);
  const Bvh sphere_tree = Bvh::build_nonrt(sphere);
  const auto pole = sphere_tree.first_hit_rt({0, 0, 0.1}, {0, 0, 0}, {}, Facing::front_only);
  ASSERT_TRUE(pole.has_value());
  EXPECT_NEAR(pole->t, 0.5, 1e-12);
}

// The nodes a short radial crossing visits, averaged over directions, on a sphere of about n
// triangles: a tree visits O(log n) of them, a scan would test all n.
double mean_nodes_visited(std::uint32_t n_lon, std::uint32_t n_lat) {
  const Mesh sphere = uv_sphere(0.05, n_lon, n_lat);
  const Bvh tree = Bvh::build_nonrt(sphere);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss;
  double total = 0.0;
  const int count = 2000;
  for (int i = 0; i < count; ++i) {
    const glm::dvec3 dir = glm::normalize(glm::dvec3{gauss(rng), gauss(rng), gauss(rng)});
    std::uint32_t visited = 0;
    EXPECT_TRUE(tree.first_hit_rt(dir * 0.051, dir * 0.049, {}, Facing::front_only, &visited).has_value());
    total += visited;
  }
  return total / count;
}

TEST(Bvh, QueryCostGrowsLogarithmically) {
  const double small = mean_nodes_visited(32, 17);    // 1,024 triangles
  const double large = mean_nodes_visited(320, 157);  // 99,840 triangles
  // 97 times the triangles: log2 grows from 10 to 16.6, a scan would cost 97 times as much.
  RecordProperty("nodes_1k", std::to_string(small));
  RecordProperty("nodes_100k", std::to_string(large));
  EXPECT_LT(large, 3.0 * small) << small << " nodes at 1k triangles, " << large << " at 100k";
}

TEST(Bvh, DepthIsNearLog2) {
  const Mesh sphere = uv_sphere(0.05, 320, 157);
  const Bvh tree = Bvh::build_nonrt(sphere);
  // Median splits: ceil(log2(99,840 / 4)) + 1 = 16 levels.
  EXPECT_LE(tree.depth(), 16u);
  EXPECT_LE(tree.depth(), Bvh::kStackSize);
}

}  // namespace
}  // namespace sandpaper::shapes
