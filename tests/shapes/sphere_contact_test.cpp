// A sphere pressed radially: the force is k d along the outward radius (Hooke's law on the exact
// sphere), although the renderer only knows the facets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/proxy.hpp"

namespace sandpaper::shapes {
namespace {

constexpr double kRadius = 0.05;   // m
constexpr double kStiffness = 500.0;  // N/m

// One fine sphere for every test here (262,144 triangles take a moment to build).
struct FineSphere {
  // 512 x 256: a quad spans pi/256 of latitude and 2 pi/512 of longitude, i.e. half-angles of
  // pi/512 both ways, so its circumscribed circle is at most r sqrt(2) pi/512 and the facet sags
  // at most r (pi/512)^2 = 1.9e-6 m below the sphere (r (1 - cos a cos b) with a = b = pi/512).
  // At the shallowest press, d = 1 mm, that is 0.19 % of k d, under the 0.25 % we allow the mesh;
  // the proxy's 1e-6 m margin adds +0.1 % the other way, leaving the 1 % bound for the renderer.
  Mesh mesh = uv_sphere(kRadius, 512, 256);
  Bvh bvh = Bvh::build_nonrt(mesh);
};

const FineSphere& fine_sphere() {
  static const FineSphere sphere;
  return sphere;
}

glm::dvec3 direction(double polar, double azimuth) {
  return {std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar)};
}

double angle_deg(const glm::dvec3& a, const glm::dvec3& b) {
  const double c = glm::dot(glm::normalize(a), glm::normalize(b));
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

TEST(SphereContact, FacetSagIsWithinTheBudget) {
  // The closed form in the comment above, checked on the mesh: every vertex is on the sphere and
  // every triangle's plane is at least r - 1.9e-6 m from the centre.
  const Mesh& mesh = fine_sphere().mesh;
  const double bound = kRadius * (1.0 - std::cos(std::numbers::pi / 512) * std::cos(std::numbers::pi / 512));
  EXPECT_LT(bound / 0.001, 0.0025);
  double worst = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const double plane_distance = glm::dot(mesh.frame(t).normal, mesh.vertex0(t));
    worst = std::max(worst, kRadius - plane_distance);
  }
  EXPECT_GT(worst, 0.0);
  EXPECT_LE(worst, bound * 1.0001);
}

TEST(SphereContact, PressedRadiallyGivesKDAlongTheRadius) {
  const FineSphere& sphere = fine_sphere();
  // Generic directions, one through a seam (a meridian edge at azimuth 0), the north pole (a
  // vertex shared by 512 triangles) and one near the south pole.
  const std::vector<glm::dvec3> directions = {
      direction(0.3, 0.1),  direction(1.0, 2.0),  direction(1.5707, 0.77), direction(2.5, 4.0),
      direction(2.9, 5.5),  direction(1.2, 0.0),  {1.0, 0.0, 0.0},          {0.0, 0.0, 1.0},
      direction(3.1, 1.3),  direction(0.77, 3.3)};
  const std::vector<double> depths = {0.001, 0.002, 0.005, 0.0075, 0.01};
  for (const glm::dvec3& dir : directions) {
    for (double depth : depths) {
      ProxyRenderer renderer(sphere.mesh, sphere.bvh, {SurfaceMaterial{kStiffness}});
      // From 5 mm outside, inward in steps of 0.5 mm (the last one lands on the depth).
      double radius = kRadius + 0.005;
      renderer.reset_rt(radius * dir);
      glm::dvec3 force{0.0};
      while (radius > kRadius - depth) {
        radius = std::max(radius - 0.0005, kRadius - depth);
        force = renderer.update_rt(radius * dir);
        // Never inside the facets: the proxy stays at least r - sag from the centre.
        ASSERT_GE(glm::length(renderer.proxy_rt()), kRadius - 2e-6) << "direction " << dir.x << "," << dir.y << ","
                                                                     << dir.z << " depth " << depth;
      }
      SCOPED_TRACE(testing::Message() << "direction (" << dir.x << ", " << dir.y << ", " << dir.z << "), depth "
                                      << depth * 1e3 << " mm");
      EXPECT_NEAR(glm::length(force), kStiffness * depth, 0.01 * kStiffness * depth);
      EXPECT_LT(angle_deg(force, dir), 1.0);
      EXPECT_TRUE(renderer.contact_rt().in_contact);
    }
  }
}

TEST(SphereContact, AJumpThroughTheWholeSphereDoesNotPopThrough) {
  const FineSphere& sphere = fine_sphere();
  ProxyRenderer renderer(sphere.mesh, sphere.bvh, {SurfaceMaterial{kStiffness}});
  const glm::dvec3 dir = direction(1.1, 0.4);
  renderer.reset_rt((kRadius + 0.002) * dir);
  // The goal is teleported to the far side, 1 mm inside the opposite surface.
  const glm::dvec3 force = renderer.update_rt(-(kRadius - 0.001) * dir);
  EXPECT_GE(glm::dot(renderer.proxy_rt(), dir), kRadius - 2e-6);
  EXPECT_LT(angle_deg(force, dir), 1.0);
  EXPECT_NEAR(glm::length(force), kStiffness * (2 * kRadius - 0.001), 0.01 * kStiffness * (2 * kRadius - 0.001));
}

TEST(SphereContact, LeavingTheSurfaceGivesNoForce) {
  const FineSphere& sphere = fine_sphere();
  ProxyRenderer renderer(sphere.mesh, sphere.bvh, {SurfaceMaterial{kStiffness}});
  const glm::dvec3 dir = direction(0.9, 2.2);
  renderer.reset_rt((kRadius + 0.002) * dir);
  EXPECT_GT(glm::length(renderer.update_rt((kRadius - 0.002) * dir)), 0.9);
  EXPECT_EQ(glm::length(renderer.update_rt((kRadius + 0.0001) * dir)), 0.0);
  EXPECT_FALSE(renderer.contact_rt().in_contact);
  EXPECT_EQ(renderer.proxy_rt(), (kRadius + 0.0001) * dir);
}

}  // namespace
}  // namespace sandpaper::shapes
