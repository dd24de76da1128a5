// Coulomb friction on the plane z = 0 (Ruspini, Kolarov & Khatib 1997): pressed with a
// normal force N, the proxy sticks while the lateral force k x stays within mu_s N, slides with a
// lateral force of mu_k N, and sticks again when the device stops.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/proxy.hpp"

namespace sandpaper::shapes {
namespace {

constexpr double kStiffness = 1000.0;  // N/m
constexpr double kStatic = 0.6;
constexpr double kKinetic = 0.4;
constexpr double kDepth = 0.002;  // m: N = k d = 2 N (plus k times the 1e-6 m margin)

struct Floor {
  // A grid, so that sliding crosses triangle edges.
  Mesh mesh = plane(0.2, 0.2, 8, 8);
  Bvh bvh = Bvh::build_nonrt(mesh);
};

// Presses straight down at (x, y) to the depth, from 3 mm above.
void press_down(ProxyRenderer& renderer, double x, double y) {
  renderer.reset_rt({x, y, 0.003});
  for (int i = 1; i <= 10; ++i) renderer.update_rt({x, y, 0.003 - (0.003 + kDepth) * i / 10.0});
}

TEST(Friction, SticksSlidesAtMuKAndSticksAgain) {
  const Floor floor;
  ProxyRenderer renderer(floor.mesh, floor.bvh, {SurfaceMaterial{kStiffness, 0.0, kStatic, kKinetic}});
  const double x0 = 0.0123, y0 = -0.0071;
  press_down(renderer, x0, y0);
  const glm::dvec3 stuck_at = renderer.proxy_rt();
  EXPECT_NEAR(stuck_at.x, x0, 1e-12);
  EXPECT_NEAR(stuck_at.y, y0, 1e-12);

  // Lateral steps of 0.02 mm in +x. Before the slip the proxy does not move: F_x = -k x, and
  // |F_x| <= mu_s N. The first step past mu_s N / k = 1.2 mm slips.
  double x = x0;
  int step = 0;
  bool slipped = false;
  for (; step < 200 && !slipped; ++step) {
    x += 0.00002;
    const glm::dvec3 force = renderer.update_rt({x, y0, -kDepth});
    const double normal = force.z;
    EXPECT_NEAR(normal, kStiffness * (kDepth + 1e-6), 1e-9);
    if (renderer.contact_rt().sliding) {
      slipped = true;
      EXPECT_GT(kStiffness * (x - x0), kStatic * normal);
      EXPECT_NEAR(-force.x, kKinetic * normal, 0.01 * kKinetic * normal);
    } else {
      EXPECT_EQ(renderer.proxy_rt(), stuck_at);
      EXPECT_NEAR(-force.x, kStiffness * (x - x0), 1e-9);
      EXPECT_LE(-force.x, kStatic * normal * (1 + 1e-9));
    }
  }
  ASSERT_TRUE(slipped);
  EXPECT_NEAR(x - x0, kStatic * kStiffness * (kDepth + 1e-6) / kStiffness, 0.00002 + 1e-9);

  // Sliding steadily at 0.05 mm a tick for 50 mm (across the grid's triangles): mu_k N.
  for (int i = 0; i < 1000; ++i) {
    x += 0.00005;
    const glm::dvec3 force = renderer.update_rt({x, y0, -kDepth});
    ASSERT_TRUE(renderer.contact_rt().sliding) << "tick " << i;
    EXPECT_NEAR(-force.x, kKinetic * force.z, 0.01 * kKinetic * force.z) << "tick " << i;
    EXPECT_NEAR(force.y, 0.0, 1e-9);
    EXPECT_GE(renderer.proxy_rt().z, 0.0);
  }

  // Stopping: the device is held still, the goal is inside the kinetic cone, the proxy sticks.
  const glm::dvec3 held{x, y0, -kDepth};
  const glm::dvec3 force_held = renderer.update_rt(held);
  const glm::dvec3 rest = renderer.proxy_rt();
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(renderer.update_rt(held), force_held);
    EXPECT_FALSE(renderer.contact_rt().sliding);
    EXPECT_EQ(renderer.proxy_rt(), rest);
  }
  // Stuck again means static friction again: pulling to 1.0 mm ahead (beyond mu_k N / k = 0.8 mm,
  // within mu_s N / k = 1.2 mm) does not move it, and back 0.3 mm does not either.
  EXPECT_NEAR(renderer.update_rt({rest.x + 0.001, y0, -kDepth}).x, -kStiffness * 0.001, 1e-9);
  EXPECT_EQ(renderer.proxy_rt(), rest);
  EXPECT_FALSE(renderer.contact_rt().sliding);
  EXPECT_NEAR(renderer.update_rt({rest.x - 0.0003, y0, -kDepth}).x, kStiffness * 0.0003, 1e-9);
  EXPECT_EQ(renderer.proxy_rt(), rest);
  // Past mu_s it slides again, and lands on the kinetic cone.
  const glm::dvec3 force = renderer.update_rt({rest.x + 0.0013, y0, -kDepth});
  EXPECT_TRUE(renderer.contact_rt().sliding);
  EXPECT_NEAR(-force.x, kKinetic * force.z, 1e-9);
}

TEST(Friction, OpposesTheMotionInAnyDirection) {
  const Floor floor;
  ProxyRenderer renderer(floor.mesh, floor.bvh, {SurfaceMaterial{kStiffness, 0.0, kStatic, kKinetic}});
  press_down(renderer, 0.0, 0.0);
  const glm::dvec3 direction = glm::normalize(glm::dvec3{-0.6, 0.8, 0.0});
  glm::dvec3 force{0.0};
  for (int i = 1; i <= 400; ++i) force = renderer.update_rt(direction * (0.00005 * i) + glm::dvec3{0, 0, -kDepth});
  ASSERT_TRUE(renderer.contact_rt().sliding);
  const glm::dvec3 lateral{force.x, force.y, 0.0};
  EXPECT_NEAR(glm::length(lateral), kKinetic * force.z, 0.01 * kKinetic * force.z);
  EXPECT_NEAR(glm::dot(glm::normalize(lateral), -direction), 1.0, 1e-9);
}

TEST(Friction, WithoutFrictionTheProxyStaysAboveTheDevice) {
  const Floor floor;
  ProxyRenderer renderer(floor.mesh, floor.bvh, {SurfaceMaterial{kStiffness}});
  press_down(renderer, 0.0, 0.0);
  const glm::dvec3 force = renderer.update_rt({0.004, 0.001, -kDepth});
  EXPECT_NEAR(force.x, 0.0, 1e-12);
  EXPECT_NEAR(force.y, 0.0, 1e-12);
  EXPECT_NEAR(force.z, kStiffness * (kDepth + 1e-6), 1e-9);
}

}  // namespace
}  // namespace sandpaper::shapes
