// How the servo loop stops: bad configuration, device faults and non-finite forces.
#include <gtest/gtest.h>

#include <atomic>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"

namespace sandpaper::runtime {
namespace {

using testing::grating;
using testing::program_of;
using testing::ScriptedDevice;
using testing::spring;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

ServoConfig config(double rate_hz, double duration_s) {
  ServoConfig c;
  c.rate_hz = rate_hz;
  c.duration_s = duration_s;
  // No start ramp: these checks compare each tick's force with the law's (SafetyRamp tests the ramp).
  c.ramp_s = 0;
  return c;
}

std::string rejection(const ServoConfig& c, const DeviceLimits& limits) {
  try {
    validate_config(c, limits);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ValidateConfig, RateMustLieBetween900HzAnd10kHz) {
  const DeviceLimits sim = sim_device_limits();
  EXPECT_NO_THROW(validate_config(config(900, 1), sim));
  EXPECT_NO_THROW(validate_config(config(10000, 1), sim));
  EXPECT_THROW(validate_config(config(899, 1), sim), std::invalid_argument);
  EXPECT_THROW(validate_config(config(10001, 1), sim), std::invalid_argument);
  EXPECT_THROW(validate_config(config(kNaN, 1), sim), std::invalid_argument);
  const std::string message = rejection(config(899, 1), sim);
  EXPECT_NE(message.find("899 Hz"), std::string::npos) << message;
  EXPECT_NE(message.find("900 Hz"), std::string::npos) << message;
  EXPECT_NE(message.find("10000 Hz"), std::string::npos) << message;
}

TEST(ValidateConfig, RateMustAlsoSuitTheDevice) {
  DeviceLimits slow = sim_device_limits();
  slow.name = "slow-stick";
  slow.max_rate_hz = 2000;
  EXPECT_NO_THROW(validate_config(config(2000, 1), slow));
  const std::string message = rejection(config(2001, 1), slow);
  EXPECT_NE(message.find("slow-stick"), std::string::npos) << message;
  EXPECT_NE(message.find("2000 Hz"), std::string::npos) << message;
}

TEST(ValidateConfig, DurationMustBeFiniteAndZeroOnlyWithAStopRequest) {
  const DeviceLimits sim = sim_device_limits();
  for (double bad : {0.0, -1.0, kNaN, kInf, 1e-6}) EXPECT_THROW(validate_config(config(1000, bad), sim), std::invalid_argument) << bad;
  // The timing statistics no longer grow with the run: a day at 10 kHz is as good as a second.
  EXPECT_NO_THROW(validate_config(config(10000, 86400.0), sim));
  // 0 plays until stopped, which needs something to stop it.
  std::atomic<bool> stop{false};
  ServoConfig until_stopped = config(1000, 0.0);
  until_stopped.stop_request = &stop;
  EXPECT_NO_THROW(validate_config(until_stopped, sim));
  EXPECT_NE(rejection(config(1000, 0.0), sim).find("needs a stop request"), std::string::npos);
}

TEST(ValidateConfig, SpinMarginGuardAndCpu) {
  const DeviceLimits sim = sim_device_limits();
  ServoConfig c = config(10000, 1.0);
  c.spin_margin_s = 100e-6;  // a whole period: allowed (spins every period)
  EXPECT_NO_THROW(validate_config(c, sim));
  c.spin_margin_s = 101e-6;
  EXPECT_NE(rejection(c, sim).find("spin margin"), std::string::npos);
  c.spin_margin_s = -1e-6;
  EXPECT_THROW(validate_config(c, sim), std::invalid_argument);
  c = config(1000, 1.0);
  c.deadline_guard_periods = -1;
  EXPECT_NE(rejection(c, sim).find("deadline guard"), std::string::npos);
  c.deadline_guard_periods = 0;  // 0: the default, 50 ms
  EXPECT_NO_THROW(validate_config(c, sim));
  EXPECT_DOUBLE_EQ(deadline_guard_s(c), 0.05);
  c.deadline_guard_periods = 20;
  EXPECT_DOUBLE_EQ(deadline_guard_s(c), 0.02);
  c = config(1000, 1.0);
  c.cpu = 1023;  // no machine this runs on has it, and this process may not run there
  EXPECT_NE(rejection(c, sim).find("CPU 1023"), std::string::npos);
  c.cpu = -2;
  EXPECT_THROW(validate_config(c, sim), std::invalid_argument);
}

TEST(ValidateConfig, RunRefusesBeforeTouchingTheDevice) {
  const auto program = program_of({spring(1.0)});
  PatchEvaluator evaluator(program);
  ScriptedDevice device;
  VirtualClock clock;
  EXPECT_THROW(run_servo_loop(device, evaluator, clock, config(800, 1.0)), std::invalid_argument);
  EXPECT_EQ(device.reads, 0u);
  EXPECT_TRUE(device.writes.empty());
}

TEST(ServoFaults, NonFiniteForceStopsAfterOneTickAndLeavesZeroForce) {
  const auto program = program_of({spring(100.0), grating(0.003, 0.0, {1.0f, std::nanf("")})});
  PatchEvaluator evaluator(program);
  SimJoystick joystick(sim_device_limits(), HandScript{}, 100);
  VirtualClock clock;
  const ServoReport report = run_servo_loop(joystick, evaluator, clock, config(1000, 0.1));
  EXPECT_EQ(report.stop_reason, "non-finite force");
  EXPECT_EQ(report.ticks, 1u);
  EXPECT_EQ(joystick.ticks_played(), 1u);
  ASSERT_EQ(joystick.records().size(), 1u);
  EXPECT_EQ(joystick.records()[0].force_N, glm::dvec2(0, 0));
  EXPECT_EQ(report.felt_max_lateral_force_N, 0.0);
}

TEST(ServoFaults, NonFiniteForceCommandsOnlyZero) {
  const auto program = program_of({grating(0.003, 0.0, {std::nanf(""), 1.0f})});
  PatchEvaluator evaluator(program);
  ScriptedDevice device;
  VirtualClock clock;
  const ServoReport report = run_servo_loop(device, evaluator, clock, config(1000, 0.1));
  EXPECT_EQ(report.stop_reason, "non-finite force");
  EXPECT_EQ(report.ticks, 1u);
  ASSERT_FALSE(device.writes.empty());
  for (const glm::dvec2 f : device.writes) EXPECT_EQ(f, glm::dvec2(0, 0));
}

TEST(ServoFaults, FailedReadStopsTheLoopWithZeroForce) {
  const auto program = program_of({spring(100.0)});
  PatchEvaluator evaluator(program);
  ScriptedDevice device({0.01, 0.0});
  device.fail_read_at = 6;
  VirtualClock clock;
  const ServoReport report = run_servo_loop(device, evaluator, clock, config(1000, 1.0));
  EXPECT_EQ(report.stop_reason, "device read failed");
  EXPECT_EQ(report.ticks, 6u);
  EXPECT_EQ(device.reads, 6u);
  // Five good ticks, the fault's zero, the closing zero.
  ASSERT_EQ(device.writes.size(), 7u);
  EXPECT_NEAR(device.writes[4].x, -1.0, 1e-12);
  EXPECT_EQ(device.writes[5], glm::dvec2(0, 0));
  EXPECT_EQ(device.writes[6], glm::dvec2(0, 0));
}

TEST(ServoFaults, FailedWriteStopsTheLoop) {
  const auto program = program_of({spring(100.0)});
  PatchEvaluator evaluator(program);
  ScriptedDevice device({0.01, 0.0});
  device.fail_write_at = 3;
  VirtualClock clock;
  const ServoReport report = run_servo_loop(device, evaluator, clock, config(1000, 1.0));
  EXPECT_EQ(report.stop_reason, "device write failed");
  EXPECT_EQ(report.ticks, 3u);
  ASSERT_EQ(device.writes.size(), 4u);
  EXPECT_EQ(device.writes.back(), glm::dvec2(0, 0));
}

}  // namespace
}  // namespace sandpaper::runtime
