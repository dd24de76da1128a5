// The renderer's update runs on the servo thread: no heap allocation and no lock, on the fine sphere,
// with friction (both solves), over 10,000 updates (tests/support/allocation_counter).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>

#include "allocation_counter.hpp"
#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/proxy.hpp"
#include "sandpaper/shapes/surface_relief.hpp"
#include "sandpaper/shapes/textured_contact.hpp"

namespace sandpaper::shapes {
namespace {

TEST(ProxyRealTime, TenThousandUpdatesAllocateNothingAndLockNothing) {
  const double r = 0.05;
  const Mesh mesh = uv_sphere(r, 512, 256);
  const Bvh bvh = Bvh::build_nonrt(mesh);
  ProxyRenderer renderer(mesh, bvh, {SurfaceMaterial{500.0, 0.5, 0.3, 0.2}});
  // A circle of 5 mm radius about the point (polar 1 rad, azimuth 0.5 rad), pressed 1 mm in: half a
  // turn in 500 updates, then held for 500, so that the proxy slides and sticks in turn.
  const glm::dvec3 centre{std::sin(1.0) * std::cos(0.5), std::sin(1.0) * std::sin(0.5), std::cos(1.0)};
  const glm::dvec3 u = glm::normalize(glm::cross(centre, glm::dvec3{0, 0, 1}));
  const glm::dvec3 v = glm::cross(centre, u);
  auto device_at = [&](int i) {
    const int moving = (i / 1000) * 500 + std::min(i % 1000, 500);
    const double a = 2.0 * std::numbers::pi * moving / 1000.0;
    return glm::normalize(centre * r + 0.005 * (std::cos(a) * u + std::sin(a) * v)) * (r - 0.001);
  };
  renderer.reset_rt(centre * (r + 0.002));
  renderer.update_rt(device_at(0));
  double max_force = 0.0;
  int sliding = 0;
  sandpaper::test::RtViolations violations;
  {
    sandpaper::test::CountedRtViolations counted;
    for (int i = 1; i <= 10000; ++i) {
      const glm::dvec3 f = renderer.update_rt(device_at(i), glm::dvec3{0.01, 0.0, 0.0});
      max_force = std::max(max_force, glm::length(f));
      sliding += renderer.contact_rt().sliding ? 1 : 0;
    }
    violations = counted.stop();
  }
  EXPECT_EQ(violations.allocations, 0u);
  EXPECT_EQ(violations.locks, 0u);
  // It did render contact, with both sticking and sliding.
  EXPECT_GT(max_force, 0.4);
  EXPECT_GT(sliding, 1000);
  EXPECT_LT(sliding, 9000);
}

// The same with a relief and the lateral texture on the sphere (a grating and a repeating height
// field, laid by its UVs), so that the relief's lookups and its slope's hold at the poles are in it.
TEST(ProxyRealTime, TenThousandUpdatesWithAReliefAllocateNothingAndLockNothing) {
  const double r = 0.05;
  const Mesh mesh = uv_sphere(r, 256, 128);
  const Bvh bvh = Bvh::build_nonrt(mesh);
  schema::PatchProgram p;
  p.size_m[0] = p.size_m[1] = 0.06;
  schema::GratingTerm g;
  g.period_m = 0.004;
  g.orientation_rad = 0.4;
  for (int i = 0; i < 64; ++i) g.force_N.push_back(static_cast<float>(-0.3 * std::sin(2 * std::numbers::pi * i / 64)));
  p.terms.push_back(g);
  schema::HeightFieldTerm h;
  h.nx = h.ny = 8;
  h.spacing_m[0] = h.spacing_m[1] = 0.001;
  h.repeat = true;
  for (int i = 0; i < 64; ++i) {
    h.force_x_N.push_back(static_cast<float>(0.1 * std::sin(i)));
    h.force_y_N.push_back(static_cast<float>(0.1 * std::cos(i)));
  }
  p.terms.push_back(h);
  p.max_lateral_force_N = 0.4;
  const glm::dvec2 uv_size{2 * std::numbers::pi * r, std::numbers::pi * r};
  std::vector<std::optional<SurfaceTexture>> textures(1);
  textures[0] = SurfaceTexture::for_program_nonrt(p, uv_size);
  std::vector<std::optional<SurfaceRelief>> reliefs(1);
  reliefs[0] = SurfaceRelief::for_program_nonrt(p, 0.0005, uv_size);
  TexturedContact contact(mesh, bvh, {SurfaceMaterial{800.0, 0.5, 0.3, 0.2}}, std::move(textures), std::move(reliefs));
  // Round the sphere near a pole (polar angle 0.1 to 0.3 rad), pressed 1 mm in.
  auto device_at = [&](int i) {
    const double polar = 0.2 + 0.1 * std::sin(i * 0.01), azimuth = i * 0.003;
    return (r - 0.001) * glm::dvec3{std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar)};
  };
  contact.reset_rt(device_at(0) * 1.1);
  contact.update_rt(device_at(0));
  double largest_relief = 0;
  sandpaper::test::RtViolations violations;
  {
    sandpaper::test::CountedRtViolations counted;
    for (int i = 1; i <= 10000; ++i) {
      contact.update_rt(device_at(i), glm::dvec3{0.01, 0.0, 0.0});
      largest_relief = std::max(largest_relief, glm::length(contact.relief_force_rt()));
    }
    violations = counted.stop();
  }
  EXPECT_EQ(violations.allocations, 0u);
  EXPECT_EQ(violations.locks, 0u);
  EXPECT_GT(largest_relief, 0.05);  // the relief was felt
}

}  // namespace
}  // namespace sandpaper::shapes
