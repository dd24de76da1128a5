// The proxy's neighbourhood of triangles must answer every cast it covers exactly as the tree
// does (the same crossing, bit for bit, and the same triangle), so that keeping it changes the cost
// of a tick and never its force.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/nearby_triangles.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/proxy.hpp"

namespace sandpaper::shapes {
namespace {

constexpr double kRadius = 0.05;

glm::dvec3 random_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return glm::normalize(glm::dvec3{n(rng), n(rng), n(rng)});
}

// Two shells 0.4 mm apart (50 and 49.6 mm), so that a cast through the outer one meets the inner
// one behind it: what the proxy's excluded planes ask for.
Mesh two_shells() {
  MeshData outer = uv_sphere_data(kRadius, 200, 101);
  const MeshData inner = uv_sphere_data(kRadius - 0.4e-3, 200, 101);
  const auto base = static_cast<std::uint32_t>(outer.vertices.size());
  outer.vertices.insert(outer.vertices.end(), inner.vertices.begin(), inner.vertices.end());
  outer.uvs.insert(outer.uvs.end(), inner.uvs.begin(), inner.uvs.end());
  for (auto t : inner.triangles) outer.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  outer.materials.insert(outer.materials.end(), inner.materials.begin(), inner.materials.end());
  return Mesh::build_nonrt(std::move(outer));
}

// Segments from points near a sphere's surface (where the proxy casts), short and long, along the
// surface and through it, on a 100k-triangle ball and on two shells: each one the neighbourhood
// covers is answered as the tree answers it, also with the triangle found excluded.
TEST(NearbyTriangles, AnswersEveryCoveredCastAsTheTreeDoes) {
  std::mt19937_64 rng(20261130);
  std::uniform_real_distribution<double> height(-0.8e-3, 0.8e-3), step(-1.5e-3, 1.5e-3), unit(0.0, 1.0);
  int covered = 0, hits = 0, excluded_hits = 0;
  double sizes = 0, radii = 0, gathers = 0;
  NearbyTriangles nearby;
  for (const Mesh& mesh : {uv_sphere(kRadius, 320, 157), two_shells()}) {
    const Bvh bvh = Bvh::build_nonrt(mesh);
    for (int i = 0; i < 400; ++i) {
      const glm::dvec3 centre = random_direction(rng) * (kRadius + height(rng));
      ASSERT_TRUE(nearby.gather_rt(bvh, centre, 1e-3));
      sizes += static_cast<double>(nearby.size());
      radii += nearby.radius_m();
      ++gathers;
      for (int k = 0; k < 50; ++k) {
        const glm::dvec3 a = centre + glm::dvec3{step(rng), step(rng), step(rng)} * 0.65;
        const glm::dvec3 b = unit(rng) < 0.5 ? centre + glm::dvec3{step(rng), step(rng), step(rng)} * 0.65
                                            : a * ((kRadius - 0.9e-3) / glm::length(a));
        for (Facing facing : {Facing::front_only, Facing::both}) {
          if (!nearby.covers_rt(a, b)) continue;
          ++covered;
          const auto want = bvh.first_hit_rt(a, b, {}, facing);
          const auto got = nearby.first_hit_rt(a, b, {}, facing);
          ASSERT_EQ(got.has_value(), want.has_value()) << i << " " << k;
          if (!want) continue;
          ++hits;
          ASSERT_EQ(got->triangle, want->triangle);
          ASSERT_EQ(got->t, want->t);
          ASSERT_EQ(got->point_m, want->point_m);
          const std::uint32_t skip[] = {want->triangle};
          const auto want2 = bvh.first_hit_rt(a, b, skip, facing);
          const auto got2 = nearby.first_hit_rt(a, b, skip, facing);
          ASSERT_EQ(got2.has_value(), want2.has_value());
          if (want2) {
            ++excluded_hits;
            ASSERT_EQ(got2->triangle, want2->triangle);
            ASSERT_EQ(got2->t, want2->t);
          }
        }
      }
    }
  }
  // The comparison is only worth something if many casts were covered and crossed a surface.
  EXPECT_GT(covered, 20000);
  EXPECT_GT(hits, 5000);
  EXPECT_GT(excluded_hits, 500);
  std::printf("[figures] %d covered casts, %d crossing, %d crossing a second surface; %.1f triangles gathered "
              "in a cube of %.3f mm half-side on average\n",
              covered, hits, excluded_hits, sizes / gathers, 1e3 * radii / gathers);
}

TEST(NearbyTriangles, CoversOnlySegmentsInsideItsCube) {
  const Mesh mesh = plane(0.1, 0.1, 8, 8);
  const Bvh bvh = Bvh::build_nonrt(mesh);
  NearbyTriangles nearby;
  EXPECT_FALSE(nearby.covers_rt(glm::dvec3{0.0}, glm::dvec3{0.0}));  // nothing gathered yet
  ASSERT_TRUE(nearby.gather_rt(bvh, glm::dvec3{0.0}, 1e-3));
  EXPECT_TRUE(nearby.covers_rt(glm::dvec3{-0.9e-3, 0.0, 0.5e-3}, glm::dvec3{0.9e-3, 0.9e-3, -0.9e-3}));
  EXPECT_FALSE(nearby.covers_rt(glm::dvec3{0.0}, glm::dvec3{0.0, 0.0, -1.1e-3}));
  EXPECT_FALSE(nearby.covers_rt(glm::dvec3{1.1e-3, 0.0, 0.0}, glm::dvec3{0.0}));
  EXPECT_TRUE(nearby.inside_rt(glm::dvec3{0.4e-3, 0.0, 0.0}, 0.5));
  EXPECT_FALSE(nearby.inside_rt(glm::dvec3{0.6e-3, 0.0, 0.0}, 0.5));
  nearby.clear_rt();
  EXPECT_FALSE(nearby.covers_rt(glm::dvec3{0.0}, glm::dvec3{1e-6, 0.0, 0.0}));
}

// A neighbourhood denser than the capacity is gathered at a smaller size, and one still too dense
// at an eighth of it is refused, so that every cast goes to the tree.
TEST(NearbyTriangles, ShrinksWhenCrowdedAndGivesUpWhenStillCrowded) {
  const Bvh grid = Bvh::build_nonrt(plane(0.01, 0.01, 40, 40));  // 0.5 mm squares, 3,200 triangles
  NearbyTriangles nearby;
  ASSERT_TRUE(nearby.gather_rt(grid, glm::dvec3{0.1e-3, 0.1e-3, 0.0}, 4e-3));
  EXPECT_LT(nearby.radius_m(), 4e-3);
  EXPECT_LE(nearby.size(), NearbyTriangles::kCapacity);
  EXPECT_GT(nearby.size(), 0u);
  // 200 triangles stacked at one spot: no cube about it holds fewer than all of them.
  MeshData data;
  for (std::uint32_t i = 0; i < 200; ++i) {
    const double z = 1e-6 * i;
    const auto base = static_cast<std::uint32_t>(data.vertices.size());
    data.vertices.push_back({-1e-3, -1e-3, z});
    data.vertices.push_back({1e-3, -1e-3, z});
    data.vertices.push_back({0.0, 1e-3, z});
    data.triangles.push_back({base, base + 1, base + 2});
  }
  const Mesh stack = Mesh::build_nonrt(std::move(data));
  const Bvh stacked = Bvh::build_nonrt(stack);
  EXPECT_FALSE(nearby.gather_rt(stacked, glm::dvec3{0.0}, 1e-3));
  EXPECT_FALSE(nearby.valid());
  EXPECT_FALSE(nearby.covers_rt(glm::dvec3{0.0, 0.0, 1e-3}, glm::dvec3{0.0, 0.0, -1e-4}));
}

// Whole runs of the proxy, with and without friction, give bit-identical forces with the
// neighbourhood and without it (a neighbourhood too small to cover any cast), while the
// neighbourhood was really in use.
TEST(NearbyTriangles, TheProxyFeelsTheSameWithItAndWithout) {
  const Mesh mesh = uv_sphere(kRadius, 320, 157);
  const Bvh bvh = Bvh::build_nonrt(mesh);
  for (const SurfaceMaterial& material : {SurfaceMaterial{500.0}, SurfaceMaterial{500.0, 0.0, 0.4, 0.3}}) {
    ProxyOptions tree_only;
    tree_only.neighbourhood_m = 1e-15;
    ProxyRenderer with(mesh, bvh, {material});
    ProxyRenderer without(mesh, bvh, {material}, tree_only);
    const glm::dvec3 centre = glm::normalize(glm::dvec3{0.3, 0.5, 0.8});
    const glm::dvec3 u = glm::normalize(glm::cross(centre, glm::dvec3{0, 0, 1})), v = glm::cross(centre, u);
    const glm::dvec3 start = centre * (kRadius + 0.003);
    with.reset_rt(start);
    without.reset_rt(start);
    int in_contact = 0, gathered = 0;
    for (int k = 0; k < 6000; ++k) {
      // Down onto the ball, round a wobbling circle on it, and up off it again.
      const double a = 2.0 * std::numbers::pi * k / 1500.0;
      const double depth = k < 500 ? 0.003 - 4.5e-3 * k / 500.0 : (k > 5500 ? -1.5e-3 + 9e-3 * (k - 5500) / 500.0 : -1.5e-3 + 1e-3 * std::sin(a / 3.0));
      const glm::dvec3 device =
          glm::normalize(centre * kRadius + 0.01 * (std::cos(a) * u + std::sin(1.3 * a) * v)) * (kRadius + depth);
      const glm::dvec3 f1 = with.update_rt(device), f2 = without.update_rt(device);
      ASSERT_EQ(f1, f2) << "tick " << k;
      ASSERT_EQ(with.proxy_rt(), without.proxy_rt()) << "tick " << k;
      if (with.contact_rt().in_contact) ++in_contact;
      if (with.nearby_rt().valid() && with.nearby_rt().size() > 0) ++gathered;
    }
    EXPECT_GT(in_contact, 4000);
    EXPECT_GT(gathered, 4000);
  }
}


// A deep press on a dense mesh: the device 10 mm inside a 100k-triangle ball, sliding. A cube
// about the proxy and the device would hold hundreds of triangles, so the neighbourhood is kept
// about the proxy alone and gathered again only as the proxy moves on, not on every tick; the
// forces are the tree's all the same.
TEST(NearbyTriangles, ADeepPressKeepsTheNeighbourhoodAboutTheProxy) {
  const Mesh mesh = uv_sphere(kRadius, 320, 157);
  const Bvh bvh = Bvh::build_nonrt(mesh);
  ProxyOptions tree_only;
  tree_only.neighbourhood_m = 1e-15;
  ProxyRenderer with(mesh, bvh, {SurfaceMaterial{500.0}});
  ProxyRenderer without(mesh, bvh, {SurfaceMaterial{500.0}}, tree_only);
  const glm::dvec3 centre = glm::normalize(glm::dvec3{0.3, 0.5, 0.8});
  const glm::dvec3 u = glm::normalize(glm::cross(centre, glm::dvec3{0, 0, 1})), v = glm::cross(centre, u);
  with.reset_rt(centre * (kRadius + 0.001));
  without.reset_rt(centre * (kRadius + 0.001));
  constexpr int kPress = 200, kTicks = 3200;
  std::uint64_t gathers_while_pressed = 0;
  for (int k = 0; k < kTicks; ++k) {
    // In to 10 mm over 200 ticks, then 3,000 ticks round a circle of 5 mm radius (10 um a tick).
    const double depth = k < kPress ? 0.001 - 0.011 * k / kPress : -0.010;
    const double a = k < kPress ? 0.0 : 2.0 * std::numbers::pi * (k - kPress) / 3000.0;
    const glm::dvec3 device = glm::normalize(centre * kRadius + 0.005 * (std::cos(a) - 1.0) * u + 0.005 * std::sin(a) * v) *
                              (kRadius + depth);
    const std::uint64_t before = with.nearby_rt().gathers();
    ASSERT_EQ(with.update_rt(device), without.update_rt(device)) << "tick " << k;
    ASSERT_EQ(with.proxy_rt(), without.proxy_rt()) << "tick " << k;
    ASSERT_TRUE(with.contact_rt().in_contact || k < kPress) << "tick " << k;
    if (k >= kPress) gathers_while_pressed += with.nearby_rt().gathers() - before;
  }
  // The proxy slides 31 mm over triangles about 1 mm across: one gather every few ticks at most.
  std::printf("deep press: %llu gathers in %d ticks\n", static_cast<unsigned long long>(gathers_while_pressed),
              kTicks - kPress);
  EXPECT_LT(gathers_while_pressed, static_cast<std::uint64_t>((kTicks - kPress) / 5));
  EXPECT_TRUE(with.nearby_rt().valid());
}

}  // namespace
}  // namespace sandpaper::shapes
