#include "sandpaper/runtime/sim_joystick.hpp"

#include <gtest/gtest.h>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/runtime/device_limits.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace sandpaper::runtime {
namespace {

constexpr double kSpeed = 0.05, kAmplitude = 0.03;

SimJoystick scan(double direction = 0.0, std::size_t capacity = 0) {
  return SimJoystick(sim_device_limits(), HandScript{HandPath::Scan, kSpeed, kAmplitude, direction}, capacity);
}

TEST(SimJoystick, ScanStartsOnTheCentreHeadingForward) {
  const SimJoystick joystick = scan(std::numbers::pi / 3);
  EXPECT_EQ(joystick.hand_position(0.0), glm::dvec2(0, 0));
  const glm::dvec2 p = joystick.hand_position(0.01);
  EXPECT_NEAR(p.x, 0.01 * kSpeed * std::cos(std::numbers::pi / 3), 1e-15);
  EXPECT_NEAR(p.y, 0.01 * kSpeed * std::sin(std::numbers::pi / 3), 1e-15);
}

TEST(SimJoystick, ScanTurnsAtPlusAndMinusAmplitude) {
  const SimJoystick joystick = scan();
  const double turn = kAmplitude / kSpeed;
  EXPECT_NEAR(joystick.hand_position(turn).x, kAmplitude, 1e-15);
  EXPECT_NEAR(joystick.hand_position(3 * turn).x, -kAmplitude, 1e-15);
  EXPECT_NEAR(joystick.hand_position(4 * turn).x, 0.0, 1e-15);
  double lowest = 0, highest = 0;
  for (int i = 0; i <= 100000; ++i) {
    const glm::dvec2 p = joystick.hand_position(i * 1e-4);  // 10 s: more than four laps
    lowest = std::min(lowest, p.x);
    highest = std::max(highest, p.x);
    ASSERT_EQ(p.y, 0.0);
  }
  EXPECT_NEAR(highest, kAmplitude, 1e-9);
  EXPECT_NEAR(lowest, -kAmplitude, 1e-9);
  // Just past a turn the hand has come back, not gone on.
  EXPECT_LT(joystick.hand_position(turn + 0.01).x, kAmplitude);
  EXPECT_GT(joystick.hand_position(3 * turn + 0.01).x, -kAmplitude);
}

TEST(SimJoystick, ScanMovesAtTheScriptedSpeedAlongItsDirection) {
  const double direction = -0.7;
  const SimJoystick joystick = scan(direction);
  const double dt = 1e-6;
  for (double t : {0.1, 0.35, 0.9, 1.3, 2.2, 5.05}) {
    SCOPED_TRACE(t);
    const glm::dvec2 step = joystick.hand_position(t + dt) - joystick.hand_position(t);
    EXPECT_NEAR(std::hypot(step.x, step.y) / dt, kSpeed, 1e-6);
    // Along the scan line: the step is parallel to the direction.
    EXPECT_NEAR(step.x * std::sin(direction) - step.y * std::cos(direction), 0.0, 1e-15);
  }
}

TEST(SimJoystick, CircleKeepsItsRadiusAndSpeed) {
  const SimJoystick joystick(sim_device_limits(), HandScript{HandPath::Circle, kSpeed, kAmplitude, 0.0}, 0);
  EXPECT_NEAR(joystick.hand_position(0).x, kAmplitude, 1e-15);
  EXPECT_NEAR(joystick.hand_position(0).y, 0.0, 1e-15);
  const double dt = 1e-6;
  for (int i = 0; i < 1000; ++i) {
    const double t = i * 0.0123;
    const glm::dvec2 p = joystick.hand_position(t);
    ASSERT_NEAR(std::hypot(p.x, p.y), kAmplitude, 1e-12);
    const glm::dvec2 step = joystick.hand_position(t + dt) - p;
    ASSERT_NEAR(std::hypot(step.x, step.y) / dt, kSpeed, 1e-6);
  }
  // A quarter of the circumference later the hand is at (0, amplitude): counter-clockwise.
  const glm::dvec2 quarter = joystick.hand_position(std::numbers::pi * kAmplitude / 2 / kSpeed);
  EXPECT_NEAR(quarter.x, 0.0, 1e-12);
  EXPECT_NEAR(quarter.y, kAmplitude, 1e-12);
}

TEST(SimJoystick, RecordsEachTickUpToItsCapacity) {
  SimJoystick joystick = scan(0.0, 2);
  glm::dvec2 p;
  for (int tick = 0; tick < 3; ++tick) {
    ASSERT_TRUE(joystick.read_position_rt(0.001 * tick, p));
    EXPECT_EQ(p, joystick.hand_position(0.001 * tick));
    ASSERT_TRUE(joystick.write_force_rt({1.0 * tick, -1.0}));
  }
  EXPECT_EQ(joystick.ticks_played(), 3u);
  ASSERT_EQ(joystick.records().size(), 2u);
  EXPECT_EQ(joystick.records()[1].t_s, 0.001);
  EXPECT_EQ(joystick.records()[1].position_m, joystick.hand_position(0.001));
  EXPECT_EQ(joystick.records()[1].force_N, glm::dvec2(1.0, -1.0));
}

TEST(SimJoystick, AWriteWithoutAReadIsNotATick) {
  SimJoystick joystick = scan(0.0, 4);
  glm::dvec2 p;
  joystick.read_position_rt(0.0, p);
  joystick.write_force_rt({2.0, 0.0});
  EXPECT_TRUE(joystick.write_force_rt({0.0, 0.0}));  // the loop's closing zero-force command
  EXPECT_EQ(joystick.ticks_played(), 1u);
  ASSERT_EQ(joystick.records().size(), 1u);
  EXPECT_EQ(joystick.records()[0].force_N, glm::dvec2(2.0, 0.0));
}

TEST(SimJoystick, LimitsAreTheThesisJoysticks) {
  const DeviceLimits limits = sim_device_limits();
  EXPECT_EQ(limits.name, "sim");
  EXPECT_EQ(limits.max_force_N, 10.0);
  EXPECT_EQ(limits.min_rate_hz, 900.0);
  EXPECT_EQ(limits.max_rate_hz, 10000.0);
  EXPECT_NEAR(limits.workspace_radius_m, 4.5 * 0.0254, 1e-12);  // a 9 inch circle
}

// The limits come from sim.toml's text, compiled in and read as the calibration loader reads the file.
TEST(SimJoystick, LimitsAreReadFromSimToml) {
  const auto file = calibration::load_device_file(std::string(SANDPAPER_SOURCE_DIR) + "/calibration/devices/sim.toml");
  const DeviceLimits from_file = limits_of(file), builtin = sim_device_limits();
  EXPECT_EQ(builtin.name, from_file.name);
  EXPECT_EQ(builtin.max_force_N, from_file.max_force_N);
  EXPECT_EQ(builtin.min_rate_hz, from_file.min_rate_hz);
  EXPECT_EQ(builtin.max_rate_hz, from_file.max_rate_hz);
  EXPECT_EQ(builtin.workspace_radius_m, from_file.workspace_radius_m);
  // The text reader validates as the file reader does, and names what it was given.
  try {
    (void)calibration::parse_device_text("schema = \"sandpaper-device/1\"\nname = \"sim\"\n", "embedded/sim.toml");
    ADD_FAILURE() << "a device text without force or workspace was accepted";
  } catch (const calibration::CalibrationError& e) {
    EXPECT_NE(std::string(e.what()).find("embedded/sim.toml:"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sandpaper::runtime
