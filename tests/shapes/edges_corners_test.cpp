// Edges and corners. Inside a room (a box felt from inside) every edge and corner is concave: the
// proxy comes to rest on the edge line or in the corner, held by two or three planes, and the force
// is k times the way from the device to that line or point. On a box felt from outside every edge
// is convex: the proxy rests on the face nearest the device, as the nearest point of the surface
// is. In both the proxy never crosses a face.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/proxy.hpp"

namespace sandpaper::shapes {
namespace {

constexpr double kStiffness = 1000.0;
constexpr double kHalf = 0.02;  // m: the boxes are 40 mm cubes about the origin
constexpr double kMargin = 1e-6;

double angle_deg(const glm::dvec3& a, const glm::dvec3& b) {
  const double c = glm::dot(glm::normalize(a), glm::normalize(b));
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

// How far outside the cube a point is along its worst axis: >= 0 outside or on it, < 0 inside.
double outside_cube(const glm::dvec3& p) {
  return std::max({std::abs(p.x) - kHalf, std::abs(p.y) - kHalf, std::abs(p.z) - kHalf});
}

// Moves the device in a straight line over `steps` updates and checks the proxy at each.
template <typename Check>
glm::dvec3 press(ProxyRenderer& renderer, const glm::dvec3& from, const glm::dvec3& to, int steps, Check check) {
  renderer.reset_rt(from);
  glm::dvec3 force{0.0};
  for (int i = 1; i <= steps; ++i) {
    force = renderer.update_rt(from + (to - from) * (static_cast<double>(i) / steps));
    check(renderer.proxy_rt());
  }
  return force;
}

struct Room {
  Mesh mesh = box(glm::dvec3{0.0}, glm::dvec3{kHalf}, /*inward=*/true);
  Bvh bvh = Bvh::build_nonrt(mesh);
};

struct Cube {
  Mesh mesh = box(glm::dvec3{0.0}, glm::dvec3{kHalf});
  Bvh bvh = Bvh::build_nonrt(mesh);
};

TEST(ConcaveEdge, PressedIntoItTheProxyRestsOnTheEdgeLine) {
  const Room room;
  // The edge where the floor z = -h meets the wall x = +h; pressed past both, symmetric or not.
  for (const glm::dvec3 beyond : {glm::dvec3{0.003, 0.0, 0.003}, glm::dvec3{0.001, 0.0, 0.004}, glm::dvec3{0.005, 0.0, 0.0005}}) {
    ProxyRenderer renderer(room.mesh, room.bvh, {SurfaceMaterial{kStiffness}});
    const double y = 0.0037;
    const glm::dvec3 device{kHalf + beyond.x, y, -kHalf - beyond.z};
    const glm::dvec3 force = press(renderer, {0.005, y, -0.005}, device, 40, [](const glm::dvec3& p) {
      ASSERT_LE(outside_cube(p), 0.0) << "the proxy left the room at " << p.x << "," << p.y << "," << p.z;
    });
    const glm::dvec3 edge_point{kHalf, y, -kHalf};
    SCOPED_TRACE(testing::Message() << "beyond " << beyond.x << ", " << beyond.z);
    EXPECT_LT(glm::length(renderer.proxy_rt() - edge_point), 2 * kMargin);
    EXPECT_EQ(renderer.contact_rt().constraints, 2u);
    // F = k (proxy - device): the way from the device back to the edge line.
    const glm::dvec3 expected = kStiffness * (edge_point - device);
    EXPECT_LT(glm::length(force - expected), kStiffness * 2 * kMargin);
    EXPECT_NEAR(force.y, 0.0, 1e-9);
  }
}

TEST(ConcaveCorner, PressedIntoItTheProxyRestsInTheCorner) {
  const Room room;
  ProxyRenderer renderer(room.mesh, room.bvh, {SurfaceMaterial{kStiffness}});
  const glm::dvec3 corner{kHalf, kHalf, -kHalf};
  const glm::dvec3 device = corner + glm::dvec3{0.003, 0.002, -0.004};
  const glm::dvec3 force = press(renderer, {0.004, 0.006, -0.003}, device, 50, [](const glm::dvec3& p) {
    ASSERT_LE(outside_cube(p), 0.0) << "the proxy left the room at " << p.x << "," << p.y << "," << p.z;
  });
  EXPECT_LT(glm::length(renderer.proxy_rt() - corner), 2 * kMargin);
  EXPECT_EQ(renderer.contact_rt().constraints, 3u);
  EXPECT_LT(glm::length(force - kStiffness * (corner - device)), kStiffness * 2 * kMargin);
}

TEST(ConcaveEdge, SlidingAlongTheEdgeFollowsIt) {
  const Room room;
  ProxyRenderer renderer(room.mesh, room.bvh, {SurfaceMaterial{kStiffness}});
  renderer.reset_rt({0.0, -0.015, 0.0});
  // Into the floor-wall edge, then along it across the face diagonals' ends, pressed 2 mm past each.
  for (int i = 0; i <= 300; ++i) {
    const double y = -0.015 + 0.0001 * i;
    const glm::dvec3 device = i < 20 ? glm::dvec3{0.0, -0.015, 0.0} + (i / 20.0) * glm::dvec3{kHalf + 0.002, 0.0, -kHalf - 0.002}
                                     : glm::dvec3{kHalf + 0.002, y, -kHalf - 0.002};
    const glm::dvec3 force = renderer.update_rt(device);
    ASSERT_LE(outside_cube(renderer.proxy_rt()), 0.0);
    if (i >= 20) {
      EXPECT_LT(glm::length(renderer.proxy_rt() - glm::dvec3{kHalf, y, -kHalf}), 2 * kMargin) << "step " << i;
      EXPECT_LT(glm::length(force - kStiffness * glm::dvec3{-0.002, 0.0, 0.002}), kStiffness * 2 * kMargin);
    }
  }
}

TEST(ConvexEdge, TheProxyRestsOnTheNearerFace) {
  const Cube cube;
  ProxyRenderer renderer(cube.mesh, cube.bvh, {SurfaceMaterial{kStiffness}});
  // Toward the edge x = z = +h from outside, steeper than 45 degrees: the path meets the side face
  // x = h first, and ends 1 mm inside it and 2 mm below the top: the side face is the nearer one.
  const glm::dvec3 device{kHalf - 0.001, 0.001, kHalf - 0.002};
  const glm::dvec3 force = press(renderer, {kHalf + 0.005, 0.001, kHalf + 0.005}, device, 30, [](const glm::dvec3& p) {
    ASSERT_GE(outside_cube(p), 0.0) << "the proxy entered the box at " << p.x << "," << p.y << "," << p.z;
  });
  EXPECT_NEAR(renderer.proxy_rt().x, kHalf + kMargin, 1e-12);
  EXPECT_NEAR(renderer.proxy_rt().z, device.z, 1e-12);
  EXPECT_LT(glm::length(force - kStiffness * glm::dvec3{0.001, 0.0, 0.0}), kStiffness * 2 * kMargin);
}

TEST(ConvexEdge, PressedAlongTheBisectorEitherFaceIsNearest) {
  const Cube cube;
  ProxyRenderer renderer(cube.mesh, cube.bvh, {SurfaceMaterial{kStiffness}});
  // Exactly through the edge line: the nearest surface points are on both faces, 2 mm away.
  const glm::dvec3 device{kHalf - 0.002, 0.0013, kHalf - 0.002};
  const glm::dvec3 force = press(renderer, {kHalf + 0.005, 0.0013, kHalf + 0.005}, device, 35, [](const glm::dvec3& p) {
    ASSERT_GE(outside_cube(p), 0.0) << "the proxy entered the box at " << p.x << "," << p.y << "," << p.z;
  });
  EXPECT_NEAR(glm::length(force), kStiffness * 0.002, kStiffness * 2 * kMargin);
  EXPECT_LT(std::min(angle_deg(force, {1, 0, 0}), angle_deg(force, {0, 0, 1})), 0.01);
}

TEST(ConvexCorner, PressedAlongTheDiagonalTheProxyStaysOutside) {
  const Cube cube;
  ProxyRenderer renderer(cube.mesh, cube.bvh, {SurfaceMaterial{kStiffness}});
  const glm::dvec3 corner{kHalf, kHalf, kHalf};
  const glm::dvec3 device = corner - glm::dvec3{0.002};
  const glm::dvec3 force = press(renderer, corner + glm::dvec3{0.004}, device, 30, [](const glm::dvec3& p) {
    ASSERT_GE(outside_cube(p), 0.0) << "the proxy entered the box at " << p.x << "," << p.y << "," << p.z;
  });
  // The nearest surface points are on the three faces, each 2 mm away.
  EXPECT_NEAR(glm::length(force), kStiffness * 0.002, kStiffness * 2 * kMargin);
  EXPECT_LT(std::min({angle_deg(force, {1, 0, 0}), angle_deg(force, {0, 1, 0}), angle_deg(force, {0, 0, 1})}), 0.01);
}

}  // namespace
}  // namespace sandpaper::shapes
