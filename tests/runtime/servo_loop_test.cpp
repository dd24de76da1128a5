// The servo loop on virtual time: tick count, tick times, achieved rate, overruns, clamping, filtering.
#include "sandpaper/runtime/servo_loop.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"

namespace sandpaper::runtime {
namespace {

using testing::damper;
using testing::grating;
using testing::program_of;
using testing::ScriptedDevice;
using testing::spring;
using testing::StallingClock;

ServoConfig config(double rate_hz, double duration_s) {
  ServoConfig c;
  c.rate_hz = rate_hz;
  c.duration_s = duration_s;
  // No start ramp: these checks compare each tick's force with the law's (SafetyRamp tests the ramp).
  c.ramp_s = 0;
  return c;
}

SimJoystick scan_joystick(std::size_t capacity, double speed = 0.05, double amplitude = 0.03) {
  return SimJoystick(sim_device_limits(), HandScript{HandPath::Scan, speed, amplitude, 0.0}, capacity);
}

TEST(ServoLoop, PlaysDurationTimesRateTicks) {
  const auto program = program_of({grating(0.002, 0.3, {0.0f, 1.0f, 0.0f, -1.0f})});
  PatchEvaluator evaluator(program);
  struct Case {
    double rate, duration;
    std::uint64_t ticks;
  };
  for (const Case c : {Case{1000, 2.0, 2000}, Case{2500, 0.4, 1000}, Case{900, 1.0, 900}, Case{10000, 0.0123, 123}}) {
    SCOPED_TRACE(c.rate);
    SimJoystick joystick = scan_joystick(c.ticks + 10);
    VirtualClock clock(5'000'000'000);
    const ServoReport report = run_servo_loop(joystick, evaluator, clock, config(c.rate, c.duration));
    EXPECT_EQ(report.ticks, c.ticks);
    EXPECT_EQ(joystick.ticks_played(), c.ticks);
    EXPECT_EQ(joystick.records().size(), c.ticks);
    EXPECT_EQ(report.stop_reason, "completed");
  }
}

TEST(ServoLoop, TicksHappenExactlyAtKOverRateOnVirtualTime) {
  const auto program = program_of({spring(20.0), damper(0.5)});
  PatchEvaluator evaluator(program);
  for (double rate : {1000.0, 4000.0}) {
    SCOPED_TRACE(rate);
    SimJoystick joystick = scan_joystick(2000);
    VirtualClock clock(123'456'789);
    const ServoReport report = run_servo_loop(joystick, evaluator, clock, config(rate, 2000 / rate));
    ASSERT_EQ(joystick.records().size(), 2000u);
    for (std::size_t k = 0; k < joystick.records().size(); ++k) {
      const TickRecord& record = joystick.records()[k];
      ASSERT_EQ(record.t_s, static_cast<double>(k) / rate) << "tick " << k;
      ASSERT_EQ(record.position_m, joystick.hand_position(record.t_s)) << "tick " << k;
    }
    EXPECT_NEAR(report.rate_hz, rate, 1e-9 * rate);
    const double period_us = 1e6 / rate;
    EXPECT_DOUBLE_EQ(report.period_p50_us, period_us);
    EXPECT_DOUBLE_EQ(report.period_p99_us, period_us);
    EXPECT_DOUBLE_EQ(report.period_max_us, period_us);
    EXPECT_DOUBLE_EQ(report.period_min_us, period_us);
    EXPECT_EQ(report.jitter_us, 0.0);
    EXPECT_EQ(report.compute_max_us, 0.0);  // virtual time stands still while a tick works
    EXPECT_EQ(report.overruns, 0u);
  }
}

TEST(ServoLoop, LateTicksAreCountedAsOverrunsAndTheScheduleDoesNotSlip) {
  const auto program = program_of({spring(10.0)});
  PatchEvaluator evaluator(program);
  SimJoystick joystick = scan_joystick(1000);
  // Tick 10 wakes 1.6 periods late; tick 11's deadline has then passed by 0.6 periods (also an
  // overrun); tick 12's deadline is still ahead, so the loop is back on schedule.
  StallingClock clock(10, 1'600'000);
  const ServoReport report = run_servo_loop(joystick, evaluator, clock, config(1000, 1.0));
  EXPECT_EQ(report.overruns, 2u);
  EXPECT_EQ(report.ticks, 1000u);
  EXPECT_DOUBLE_EQ(joystick.records()[10].t_s, 0.0116);
  EXPECT_DOUBLE_EQ(joystick.records()[11].t_s, 0.0116);
  EXPECT_DOUBLE_EQ(joystick.records()[12].t_s, 0.012);
  EXPECT_DOUBLE_EQ(joystick.records().back().t_s, 0.999);
  EXPECT_DOUBLE_EQ(report.period_max_us, 2600.0);
  EXPECT_DOUBLE_EQ(report.period_min_us, 0.0);
  EXPECT_GT(report.jitter_us, 0.0);
  EXPECT_NEAR(report.rate_hz, 1000.0, 1e-6);
}

TEST(ServoLoop, HalfAPeriodLateIsNotYetAnOverrun) {
  const auto program = program_of({});
  PatchEvaluator evaluator(program);
  SimJoystick joystick = scan_joystick(100);
  StallingClock on_the_edge(5, 500'000);
  EXPECT_EQ(run_servo_loop(joystick, evaluator, on_the_edge, config(1000, 0.1)).overruns, 0u);
  StallingClock past_it(5, 500'001);
  EXPECT_EQ(run_servo_loop(joystick, evaluator, past_it, config(1000, 0.1)).overruns, 1u);
}

TEST(ServoLoop, ForceMagnitudeIsClampedWithoutTurningIt) {
  // 1000 N/m over a +-30 mm scan asks for up to 30 N from a 10 N device.
  const auto program = program_of({spring(1000.0, 0.0, 0.002)});
  PatchEvaluator evaluator(program);
  SimJoystick joystick = scan_joystick(2000);
  VirtualClock clock;
  const ServoReport report = run_servo_loop(joystick, evaluator, clock, config(1000, 2.0));
  std::uint64_t over = 0;
  for (const TickRecord& record : joystick.records()) {
    HandState hand;
    hand.position_m = record.position_m;
    const glm::dvec2 wanted = evaluator.force_rt(hand, 1e-3);
    const double wanted_magnitude = std::hypot(wanted.x, wanted.y);
    const double magnitude = std::hypot(record.force_N.x, record.force_N.y);
    ASSERT_LE(magnitude, 10.0 + 1e-9);
    if (wanted_magnitude > 10.0) {
      ++over;
      ASSERT_NEAR(magnitude, 10.0, 1e-9);
      // Same direction: the cross product vanishes and the dot product is positive.
      ASSERT_NEAR(wanted.x * record.force_N.y - wanted.y * record.force_N.x, 0.0, 1e-9);
      ASSERT_GT(wanted.x * record.force_N.x + wanted.y * record.force_N.y, 0.0);
    } else {
      ASSERT_EQ(record.force_N, wanted);
    }
  }
  EXPECT_GT(over, 0u);
  EXPECT_EQ(report.clamped_ticks, over);
  EXPECT_NEAR(report.felt_max_lateral_force_N, 10.0, 1e-9);
}

TEST(ServoLoop, DamperSeesTheFilteredHandVelocity) {
  // 0.05 m/s along +x for the first 0.6 s: once the 50 Hz filter has settled the damper pushes
  // back with b v = 0.5 N. The first tick has no velocity yet.
  const auto program = program_of({damper(10.0)});
  PatchEvaluator evaluator(program);
  SimJoystick joystick = scan_joystick(600);
  VirtualClock clock;
  run_servo_loop(joystick, evaluator, clock, config(1000, 0.6));
  const auto& records = joystick.records();
  EXPECT_EQ(records[0].force_N, glm::dvec2(0, 0));
  EXPECT_LT(records[1].force_N.x, 0.0);
  EXPECT_GT(records[1].force_N.x, -0.5);
  EXPECT_NEAR(records[300].force_N.x, -0.5, 1e-9);
  EXPECT_NEAR(records[300].force_N.y, 0.0, 1e-12);
  // Monotone approach: a first-order filter on a step does not overshoot.
  for (std::size_t k = 1; k < 300; ++k) ASSERT_LE(records[k + 1].force_N.x, records[k].force_N.x + 1e-9);
}

TEST(ServoLoop, WritesZeroForceOnceAfterTheLastTick) {
  const auto program = program_of({spring(100.0)});
  PatchEvaluator evaluator(program);
  ScriptedDevice device({0.02, 0.0});
  VirtualClock clock;
  const ServoReport report = run_servo_loop(device, evaluator, clock, config(1000, 0.01));
  ASSERT_EQ(device.writes.size(), report.ticks + 1);
  EXPECT_NEAR(device.writes[9].x, -2.0, 1e-12);
  EXPECT_EQ(device.writes.back(), glm::dvec2(0, 0));
  EXPECT_NEAR(report.felt_max_lateral_force_N, 2.0, 1e-12);
  EXPECT_EQ(report.clamped_ticks, 0u);
}

}  // namespace
}  // namespace sandpaper::runtime
