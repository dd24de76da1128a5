// The nearest allowed point to a goal under one, two and three half-spaces, in closed form.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sandpaper/shapes/constraint_planes.hpp"

namespace sandpaper::shapes {
namespace {

ConstraintSet planes_of(std::initializer_list<ConstraintPlane> planes) {
  ConstraintSet set;
  for (const ConstraintPlane& p : planes) set.add(p);
  return set;
}

TEST(ConstraintPlanes, AnAllowedGoalIsItself) {
  const ConstraintSet set = planes_of({{{0, 0, 1}, 0.0, 0}});
  glm::dvec3 out{9.0};
  ASSERT_TRUE(set.project({1, 2, 3}, out));
  EXPECT_EQ(out, glm::dvec3(1, 2, 3));
}

TEST(ConstraintPlanes, OnePlaneProjectsAlongItsNormal) {
  const glm::dvec3 n = glm::normalize(glm::dvec3{1, 1, 0});
  const ConstraintSet set = planes_of({{n, 0.5, 0}});
  glm::dvec3 out;
  ASSERT_TRUE(set.project({0, 0, 7}, out));
  EXPECT_NEAR(glm::length(out - glm::dvec3{0.5 / std::sqrt(2.0), 0.5 / std::sqrt(2.0), 7}), 0.0, 1e-15);
}

TEST(ConstraintPlanes, TwoPlanesOfAConcaveEdgeGiveItsLine) {
  // Floor z >= 0 and wall x <= 1 (normal -x, offset -1): a goal past both lands on the edge line.
  const ConstraintSet set = planes_of({{{0, 0, 1}, 0.0, 0}, {{-1, 0, 0}, -1.0, 1}});
  glm::dvec3 out;
  ASSERT_TRUE(set.project({1.5, 0.3, -2.0}, out));
  EXPECT_NEAR(glm::length(out - glm::dvec3{1, 0.3, 0}), 0.0, 1e-15);
  // Past the floor only: onto the floor.
  ASSERT_TRUE(set.project({0.5, 0.3, -2.0}, out));
  EXPECT_NEAR(glm::length(out - glm::dvec3{0.5, 0.3, 0}), 0.0, 1e-15);
}

TEST(ConstraintPlanes, TwoPlanesOfAConvexEdgeGiveTheNearerFaceOrTheEdge) {
  // Top z >= 0 and side x >= 0 as half-spaces: their intersection is the region above the edge.
  const ConstraintSet set = planes_of({{{0, 0, 1}, 0.0, 0}, {{1, 0, 0}, 0.0, 1}});
  glm::dvec3 out;
  ASSERT_TRUE(set.project({-0.1, 0.0, -0.3}, out));
  EXPECT_NEAR(glm::length(out - glm::dvec3{0, 0, 0}), 0.0, 1e-15);
  ASSERT_TRUE(set.project({0.2, 0.0, -0.3}, out));
  EXPECT_NEAR(glm::length(out - glm::dvec3{0.2, 0, 0}), 0.0, 1e-15);
}

TEST(ConstraintPlanes, ThreePlanesOfACornerGiveItsPoint) {
  const ConstraintSet set = planes_of({{{0, 0, 1}, 0.0, 0}, {{-1, 0, 0}, -1.0, 1}, {{0, -1, 0}, -2.0, 2}});
  glm::dvec3 out;
  ASSERT_TRUE(set.project({1.2, 2.5, -0.1}, out));
  EXPECT_NEAR(glm::length(out - glm::dvec3{1, 2, 0}), 0.0, 1e-15);
}

TEST(ConstraintPlanes, OppositePlanesWithNoRoomBetweenHaveNoPoint) {
  const ConstraintSet set = planes_of({{{0, 0, 1}, 1.0, 0}, {{0, 0, -1}, 0.0, 1}});
  glm::dvec3 out{5.0};
  EXPECT_FALSE(set.project({0, 0, 0.5}, out));
  EXPECT_EQ(out, glm::dvec3{5.0});
}

}  // namespace
}  // namespace sandpaper::shapes
