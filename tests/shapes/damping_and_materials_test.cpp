// Damping along the contact normal, never pulling; each triangle's own material; and what the
// renderer refuses to be built with.
#include <gtest/gtest.h>

#include <stdexcept>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/proxy.hpp"

namespace sandpaper::shapes {
namespace {

TEST(Damping, AddsBTimesTheNormalSpeedAndNeverPulls) {
  const Mesh floor = plane(0.1, 0.1);
  const Bvh bvh = Bvh::build_nonrt(floor);
  ProxyRenderer renderer(floor, bvh, {SurfaceMaterial{1000.0, 2.0}});
  renderer.reset_rt({0.0, 0.0, 0.001});
  const double k_d = 1000.0 * (0.002 + 1e-6);  // the spring at 2 mm deep, with the 1e-6 m margin
  // Moving in at 0.1 m/s: the damper adds b v = 0.2 N to the spring.
  EXPECT_NEAR(renderer.update_rt({0.0, 0.0, -0.002}, {0.03, 0.0, -0.1}).z, k_d + 0.2, 1e-9);
  // Moving out at 0.5 m/s: the damper takes 1 N off; moving out at 5 m/s it would pull: zero.
  EXPECT_NEAR(renderer.update_rt({0.0, 0.0, -0.002}, {0.0, 0.0, 0.5}).z, k_d - 1.0, 1e-9);
  const glm::dvec3 force = renderer.update_rt({0.0, 0.0, -0.002}, {0.0, 0.0, 5.0});
  EXPECT_EQ(force.z, 0.0);
  // Lateral motion adds nothing (friction is the friction law's).
  EXPECT_NEAR(glm::length(renderer.update_rt({0.0, 0.0, -0.002}, {0.3, 0.2, 0.0}) - glm::dvec3{0, 0, k_d}), 0.0, 1e-9);
}

TEST(Materials, EachTriangleFeelsItsOwn) {
  // The plane's two triangles: the one below the diagonal x = y takes material 1.
  MeshData data{{{-0.1, -0.1, 0}, {0.1, -0.1, 0}, {0.1, 0.1, 0}, {-0.1, 0.1, 0}}, {{0, 1, 2}, {0, 2, 3}}, {}, {1, 0}};
  const Mesh mesh = Mesh::build_nonrt(std::move(data));
  const Bvh bvh = Bvh::build_nonrt(mesh);
  ProxyRenderer renderer(mesh, bvh, {SurfaceMaterial{300.0}, SurfaceMaterial{900.0}});
  renderer.reset_rt({0.05, -0.05, 0.001});
  EXPECT_NEAR(renderer.update_rt({0.05, -0.05, -0.001}).z, 900.0 * (0.001 + 1e-6), 1e-9);
  renderer.reset_rt({-0.05, 0.05, 0.001});
  EXPECT_NEAR(renderer.update_rt({-0.05, 0.05, -0.001}).z, 300.0 * (0.001 + 1e-6), 1e-9);
}

TEST(Materials, TheRendererRefusesWhatItCannotUse) {
  const Mesh mesh = plane(0.1, 0.1);
  const Bvh bvh = Bvh::build_nonrt(mesh);
  EXPECT_THROW(ProxyRenderer(mesh, bvh, {}), std::invalid_argument);
  EXPECT_THROW(ProxyRenderer(mesh, bvh, {SurfaceMaterial{0.0}}), std::invalid_argument);
  EXPECT_THROW(ProxyRenderer(mesh, bvh, {SurfaceMaterial{500.0, -1.0}}), std::invalid_argument);
  EXPECT_THROW(ProxyRenderer(mesh, bvh, {SurfaceMaterial{500.0, 0.0, 0.3, 0.5}}), std::invalid_argument);
  const Mesh other = uv_sphere(0.05, 8, 4);
  EXPECT_THROW(ProxyRenderer(mesh, Bvh::build_nonrt(other), {SurfaceMaterial{500.0}}), std::invalid_argument);
  ProxyOptions no_margin;
  no_margin.surface_offset_m = 0.0;
  EXPECT_THROW(ProxyRenderer(mesh, bvh, {SurfaceMaterial{500.0}}, no_margin), std::invalid_argument);
}

}  // namespace
}  // namespace sandpaper::shapes
