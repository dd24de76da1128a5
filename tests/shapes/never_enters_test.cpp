// Whatever the device does, the proxy stays on the outside of every surface: random walks with
// jumps (fixed seeds) into a cube, a room, a sphere and a thin box, with and without friction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/proxy.hpp"

namespace sandpaper::shapes {
namespace {

// Moves the device 20,000 times: mostly steps of up to 1 mm, one in 50 a jump of up to 60 mm,
// and checks `outside(proxy) >= 0` after each.
// The walk stays within 30 mm of the origin, starting from `start` (in free space).
void random_walk(const Mesh& mesh, const SurfaceMaterial& material, std::uint64_t seed, const glm::dvec3& start,
                 const std::function<double(const glm::dvec3&)>& outside) {
  const glm::dvec3 centre{0.0};
  const Bvh bvh = Bvh::build_nonrt(mesh);
  ProxyRenderer renderer(mesh, bvh, {material});
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> step(-0.001, 0.001), jump(-0.03, 0.03);
  std::uniform_int_distribution<int> which(0, 49);
  glm::dvec3 device = start;
  renderer.reset_rt(device);
  int contacts = 0;
  for (int i = 0; i < 20000; ++i) {
    if (which(rng) == 0) {
      device = centre + glm::dvec3{jump(rng), jump(rng), jump(rng)};
    } else {
      device += glm::dvec3{step(rng), step(rng), step(rng)};
      device = glm::clamp(device, centre - 0.03, centre + 0.03);
    }
    renderer.update_rt(device);
    contacts += renderer.contact_rt().in_contact ? 1 : 0;
    const glm::dvec3& p = renderer.proxy_rt();
    ASSERT_GE(outside(p), 0.0) << "update " << i << ": proxy at " << p.x << ", " << p.y << ", " << p.z;
  }
  EXPECT_GT(contacts, 2000);  // the walk spent a good part of its time pressing on the surface
}

double outside_box(const glm::dvec3& p, const glm::dvec3& half) {
  return std::max({std::abs(p.x) - half.x, std::abs(p.y) - half.y, std::abs(p.z) - half.z});
}

TEST(ProxyNeverEnters, ACube) {
  const glm::dvec3 half{0.01, 0.015, 0.02};
  for (const SurfaceMaterial& m : {SurfaceMaterial{1000.0}, SurfaceMaterial{1000.0, 0.0, 0.8, 0.5}}) {
    random_walk(box(glm::dvec3{0.0}, half), m, 11, {0.0, 0.0, 0.025},
                [&](const glm::dvec3& p) { return outside_box(p, half); });
  }
}

TEST(ProxyNeverEnters, ARoomFromInside) {
  const glm::dvec3 half{0.02, 0.02, 0.02};
  for (const SurfaceMaterial& m : {SurfaceMaterial{1000.0}, SurfaceMaterial{1000.0, 0.0, 0.8, 0.5}}) {
    random_walk(box(glm::dvec3{0.0}, half, true), m, 12, {0.0, 0.0, 0.0},
                [&](const glm::dvec3& p) { return -outside_box(p, half); });
  }
}

TEST(ProxyNeverEnters, ASphere) {
  const double r = 0.02;
  // 64 x 32: facets sag up to r (1 - cos(pi/64) cos(pi/64)) = 4.8e-5 m inside the sphere.
  const double sag = r * (1.0 - std::cos(std::numbers::pi / 64) * std::cos(std::numbers::pi / 64));
  for (const SurfaceMaterial& m : {SurfaceMaterial{1000.0}, SurfaceMaterial{1000.0, 0.0, 0.8, 0.5}}) {
    random_walk(uv_sphere(r, 64, 32), m, 13, {0.0, 0.0, 0.025},
                [&](const glm::dvec3& p) { return glm::length(p) - (r - sag); });
  }
}

TEST(ProxyNeverEnters, AThinBox) {
  const glm::dvec3 half{0.02, 0.02, 0.0005};
  for (const SurfaceMaterial& m : {SurfaceMaterial{1000.0}, SurfaceMaterial{1000.0, 0.0, 0.8, 0.5}}) {
    random_walk(box(glm::dvec3{0.0}, half), m, 14, {0.0, 0.0, 0.025},
                [&](const glm::dvec3& p) { return outside_box(p, half); });
  }
}

}  // namespace
}  // namespace sandpaper::shapes
