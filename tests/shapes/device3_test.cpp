// The 3-DOF device model (shapes/device3.hpp, hand_path3.hpp, dynamic_hand3.hpp): sim3d's limits
// are sim3d.toml's, the hand's path is where its waypoints say, and the simulated handle obeys the
// hand's mass-spring-damper against closed-form answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/shapes/device3.hpp"
#include "sandpaper/shapes/dynamic_hand3.hpp"
#include "sandpaper/shapes/hand_path3.hpp"

namespace sandpaper::shapes {
namespace {

// The shipped calibration folder (the tests run in the source tree).
const std::string kDevices = (calibration::default_calibration_dir() / "devices").string() + "/";

// sim3d.toml is the one statement of sim3d's limits: what is compiled in is what the file says, and
// the file says what its comment does (10 N, 900 Hz - 10 kHz, a sphere 9 in across).
TEST(Device3, Sim3dsLimitsAreSim3dToml) {
  const DeviceLimits3 from_file = limits3_of(calibration::load_device_file(kDevices + "sim3d.toml"));
  const DeviceLimits3& builtin = sim3d_limits();
  EXPECT_EQ(builtin.name, "sim3d");
  EXPECT_EQ(builtin.name, from_file.name);
  EXPECT_EQ(builtin.max_force_N, from_file.max_force_N);
  EXPECT_EQ(builtin.min_rate_hz, from_file.min_rate_hz);
  EXPECT_EQ(builtin.max_rate_hz, from_file.max_rate_hz);
  EXPECT_EQ(builtin.workspace.sphere, from_file.workspace.sphere);
  EXPECT_EQ(builtin.workspace.size_m, from_file.workspace.size_m);
  EXPECT_DOUBLE_EQ(builtin.max_force_N, 10.0);
  EXPECT_DOUBLE_EQ(builtin.min_rate_hz, 900.0);
  EXPECT_DOUBLE_EQ(builtin.max_rate_hz, 10000.0);
  EXPECT_TRUE(builtin.workspace.sphere);
  EXPECT_NEAR(builtin.workspace.size_m.x, 9 * 0.0254, 1e-12);
  EXPECT_EQ(open_sim3d(HandPath3({{{0, 0, 0}, {0.01, 0, 0}}}), 0).limits().name, "sim3d");
}

TEST(Device3, AFlatDeviceHasNo3DLimitsAndTheFalconsAreItsSheets) {
  try {
    limits3_of(calibration::load_device_file(kDevices + "sim.toml"));
    ADD_FAILURE() << "sim has two axes";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("device 'sim' has 2 force axis(es), not three"), std::string::npos) << e.what();
  }
  const DeviceLimits3 falcon = limits3_of(calibration::load_device_file(kDevices + "novint-falcon.toml"));
  EXPECT_FALSE(falcon.workspace.sphere);
  EXPECT_NEAR(falcon.workspace.size_m.z, 4 * 0.0254, 1e-12);
  EXPECT_NEAR(falcon.max_force_N, 2 * 4.4482216152605, 1e-9);  // 2 lbf
  // The box's corner is in, a point just past a face is not.
  EXPECT_TRUE(falcon.workspace.contains({0.0508, -0.0508, 0.0508}));
  EXPECT_FALSE(falcon.workspace.contains({0.0, 0.0509, 0.0}));
  // The sphere reaches its radius along a diagonal, not its bounding box's corner.
  const Workspace3& ball = sim3d_limits().workspace;
  const double r = 4.5 * 0.0254;
  EXPECT_TRUE(ball.contains(glm::normalize(glm::dvec3{1, 1, 1}) * (r * 0.999)));
  EXPECT_FALSE(ball.contains(glm::dvec3{r, r, r} * 0.9));
}

TEST(HandPath3, WalksItsWaypointsAtItsSpeedAndLoops) {
  // A square of side 10 mm at 20 mm/s: a lap of 40 mm in 2 s.
  const HandPath3 path({{{0, 0, 0}, {0.01, 0, 0}, {0.01, 0.01, 0}, {0, 0.01, 0}}, 0.02});
  EXPECT_NEAR(path.lap_s(), 2.0, 1e-12);
  EXPECT_NEAR(glm::length(path.position(0.25) - glm::dvec3{0.005, 0, 0}), 0, 1e-12);
  EXPECT_NEAR(glm::length(path.position(0.75) - glm::dvec3{0.01, 0.005, 0}), 0, 1e-12);
  EXPECT_NEAR(glm::length(path.position(1.75) - glm::dvec3{0, 0.005, 0}), 0, 1e-12);  // the closing side
  EXPECT_NEAR(glm::length(path.position(2.25) - path.position(0.25)), 0, 1e-12);
  EXPECT_NEAR(glm::length(path.velocity(0.75) - glm::dvec3{0, 0.02, 0}), 0, 1e-12);
  EXPECT_NEAR(glm::length(path.velocity(1.75) - glm::dvec3{0, -0.02, 0}), 0, 1e-12);
  EXPECT_THROW(HandPath3({{{0, 0, 0}}}), std::invalid_argument);
  EXPECT_THROW(HandPath3({{{0, 0, 0}, {0, 0, 0}}}), std::invalid_argument);
  EXPECT_THROW(HandPath3({{{0, 0, 0}, {1, 0, 0}}, 0.0}), std::invalid_argument);
}

TEST(HandPath3, PressAndStrokeComesDownStrokesAndLifts) {
  PressAndStroke p;
  p.point_m = {0, 0.05, 0};
  p.normal = {0, 2, 0};         // normalised
  p.direction = {1, 1, 0};      // made tangent: along x
  p.depth_m = 0.01;
  p.stroke_m = 0.04;
  p.lift_m = 0.005;
  const auto spec = press_and_stroke(p);
  ASSERT_EQ(spec.waypoints.size(), 4u);
  const glm::dvec3 expected[] = {{-0.02, 0.055, 0}, {-0.02, 0.04, 0}, {0.02, 0.04, 0}, {0.02, 0.055, 0}};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(glm::length(spec.waypoints[i] - expected[i]), 0, 1e-15) << i;
  p.direction = {0, -1, 0};
  EXPECT_THROW(press_and_stroke(p), std::invalid_argument);
}

// Along a straight path with no force the handle stays on the path: it starts there, moving with
// it. The semi-implicit step pulls toward the substep's end point, so in steady state the handle
// leads the path by one substep's travel, v h = 0.05 m/s x 0.1 ms = 5 um, reached from the start
// (no lead) with the hand's overshoot (exp(-pi zeta / sqrt(1 - zeta^2)) = 29 % at zeta = 0.37): at
// most 6.4 um, under 2 v h.
TEST(DynamicHand3, WithNoForceTheHandleRidesAStraightPath) {
  DynamicHand3 hand(sim3d_limits(), HandPath3({{{-0.05, 0, 0}, {0.05, 0.02, -0.01}}, 0.05}), {}, 1000);
  glm::dvec3 x{0.0};
  double largest = 0;
  for (int k = 0; k < 1000; ++k) {  // 1 s: 50 mm of the 102 mm segment
    const double t = k * 1e-3;
    ASSERT_TRUE(hand.read_position_rt(t, x));
    largest = std::max(largest, glm::length(x - hand.path().position(t)));
    hand.write_force_rt(glm::dvec3{0.0});
  }
  std::printf("[figures] free hand on a straight path: at most %.3g m off it\n", largest);
  EXPECT_LT(largest, 2 * 0.05 * hand.model().max_substep_s);
  EXPECT_LT(hand.energy_J(), 1e-8);  // 1/2 k_h (2 v h)^2 = 6.8 nJ
  EXPECT_EQ(hand.records().size(), 1000u);
}

// A hand holding still under a steady 1 N settles where its spring balances it, F / k_h (Hooke),
// and of the work the force did, half is stored in the hand's spring and half dissipated by its
// damper (a damped spring pulled by a step: W = F^2 / k, stored 1/2 F^2 / k).
TEST(DynamicHand3, ASteadyForceDeflectsTheHandByForceOverStiffnessAndHalfItsWorkIsDissipated) {
  runtime::HandModel model;  // 0.554 kg, 135 N/m, 6.45 N*s/m
  DynamicHand3 hand(sim3d_limits(), HandPath3({{{0, 0, 0}, {1e-12, 0, 0}}, 1e-12}), model, 0);
  const glm::dvec3 force{0.0, -0.6, 0.8};  // 1 N
  glm::dvec3 x{0.0};
  for (int k = 0; k <= 5000; ++k) {  // 5 s: 29 time constants of the hand's decay (zeta omega = 5.8 /s)
    hand.read_position_rt(k * 1e-3, x);
    hand.write_force_rt(force);
  }
  const glm::dvec3 deflection = force / model.stiffness_N_per_m;
  EXPECT_NEAR(glm::length(x - deflection), 0, 1e-3 * glm::length(deflection));
  const double work = glm::dot(force, deflection);
  EXPECT_NEAR(hand.work_on_handle_J(), work, 1e-3 * work);
  EXPECT_NEAR(hand.hand_dissipated_J(), 0.5 * work, 0.01 * 0.5 * work);
  EXPECT_NEAR(hand.energy_J(), 0.5 * work, 0.01 * 0.5 * work);
}

TEST(DynamicHand3, ABadHandIsRefused) {
  const HandPath3 path({{{0, 0, 0}, {0.01, 0, 0}}});
  runtime::HandModel m;
  m.mass_kg = 0;
  EXPECT_THROW(DynamicHand3(sim3d_limits(), path, m, 0), std::invalid_argument);
  m = {};
  m.damping_Ns_per_m = -1;
  EXPECT_THROW(DynamicHand3(sim3d_limits(), path, m, 0), std::invalid_argument);
}

}  // namespace
}  // namespace sandpaper::shapes
