// A box 1 mm thick, 50 mm wide: pressed through from above, the proxy stays on the top face and the
// force keeps growing as k times the depth below it (it does not pop through to the bottom face).
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/proxy.hpp"

namespace sandpaper::shapes {
namespace {

constexpr double kStiffness = 800.0;  // N/m
constexpr double kTop = 0.0005;       // m: the box spans z in [-0.5, 0.5] mm
constexpr double kBottom = -0.0005;
constexpr double kMargin = 1e-6;      // the renderer's default surface offset

struct ThinBox {
  Mesh mesh = box(glm::dvec3{0.0}, glm::dvec3{0.025, 0.025, 0.0005});
  Bvh bvh = Bvh::build_nonrt(mesh);
};

TEST(ThinBox, SteppingDownThroughItStaysOnTheTopFace) {
  const ThinBox thin;
  ProxyRenderer renderer(thin.mesh, thin.bvh, {SurfaceMaterial{kStiffness}});
  const double x = 0.0031, y = -0.0017;
  renderer.reset_rt({x, y, 0.005});
  double last_force = 0.0;
  int steps_in_contact = 0;
  // From 5 mm above to 10 mm below the bottom face, 0.5 mm a step.
  for (int i = 0; i <= 31; ++i) {
    const double z = 0.005 - 0.0005 * i;
    const glm::dvec3 force = renderer.update_rt({x, y, z});
    const glm::dvec3& proxy = renderer.proxy_rt();
    ASSERT_GE(proxy.z, kTop) << "step " << i;
    if (std::abs(z - kTop) < 1e-12) continue;  // touching: at most k times the margin
    if (z > kTop) {
      EXPECT_EQ(glm::length(force), 0.0) << "step " << i;
      continue;
    }
    ++steps_in_contact;
    EXPECT_NEAR(proxy.x, x, 1e-12);
    EXPECT_NEAR(proxy.y, y, 1e-12);
    EXPECT_NEAR(force.z, kStiffness * (kTop - z), kStiffness * 2 * kMargin) << "step " << i;
    EXPECT_NEAR(force.x, 0.0, 1e-9);
    EXPECT_NEAR(force.y, 0.0, 1e-9);
    EXPECT_GT(force.z, last_force) << "step " << i;
    last_force = force.z;
  }
  EXPECT_EQ(steps_in_contact, 22);
  EXPECT_NEAR(last_force, kStiffness * (kTop - (kBottom - 0.010)), kStiffness * 2 * kMargin);
}

TEST(ThinBox, OneJumpFromAboveToBelowDoesNotPopThrough) {
  const ThinBox thin;
  // Several places, corners of the face's triangles among them (the diagonal x = y splits it).
  for (const glm::dvec2 xy : {glm::dvec2{0.0, 0.0}, glm::dvec2{0.01, 0.01}, glm::dvec2{-0.02, 0.013},
                              glm::dvec2{0.0249, -0.0249}}) {
    ProxyRenderer renderer(thin.mesh, thin.bvh, {SurfaceMaterial{kStiffness}});
    renderer.reset_rt({xy.x, xy.y, kTop + 0.005});
    const double z = kBottom - 0.010;
    glm::dvec3 force = renderer.update_rt({xy.x, xy.y, z});
    EXPECT_GE(renderer.proxy_rt().z, kTop);
    EXPECT_NEAR(force.z, kStiffness * (kTop - z), kStiffness * 2 * kMargin);
    // Held there, it stays.
    force = renderer.update_rt({xy.x, xy.y, z});
    EXPECT_GE(renderer.proxy_rt().z, kTop);
    EXPECT_NEAR(force.z, kStiffness * (kTop - z), kStiffness * 2 * kMargin);
  }
}

TEST(ThinBox, FromBelowItIsFeltOnTheBottomFace) {
  const ThinBox thin;
  ProxyRenderer renderer(thin.mesh, thin.bvh, {SurfaceMaterial{kStiffness}});
  renderer.reset_rt({0.001, 0.002, kBottom - 0.003});
  const glm::dvec3 force = renderer.update_rt({0.001, 0.002, kTop + 0.002});
  EXPECT_LE(renderer.proxy_rt().z, kBottom);
  EXPECT_NEAR(force.z, -kStiffness * (kTop + 0.002 - kBottom), kStiffness * 2 * kMargin);
}

}  // namespace
}  // namespace sandpaper::shapes
