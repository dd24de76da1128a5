// The renderer's update runs on the servo thread: no heap allocation and no lock, on the fine sphere,
// with friction (both solves), over 10,000 updates (tests/support/allocation_counter).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "allocation_counter.hpp"
#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/proxy.hpp"

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

}  // namespace
}  // namespace sandpaper::shapes
