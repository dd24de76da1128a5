// The real clock and the real-time thread, briefly.
#include <gtest/gtest.h>

#include <stdexcept>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"

namespace sandpaper::runtime {
namespace {

using testing::program_of;
using testing::spring;

TEST(MonotonicClock, SleepsUntilAnAbsoluteDeadline) {
  MonotonicClock clock;
  const std::int64_t before = clock.now_ns();
  const std::int64_t deadline = before + 3'000'000;
  clock.sleep_until_ns(deadline);
  const std::int64_t after = clock.now_ns();
  EXPECT_GE(after, deadline);
  clock.sleep_until_ns(before);  // a deadline already passed returns at once
  EXPECT_GE(clock.now_ns(), after);
}

TEST(ServoThread, PlaysTheWholeRunOnTheMonotonicClock) {
  const auto program = program_of({spring(50.0)});
  PatchEvaluator evaluator(program);
  SimJoystick joystick(sim_device_limits(), HandScript{}, 100);
  ServoConfig config;
  config.rate_hz = 1000;
  config.duration_s = 0.05;
  const ServoReport report = run_servo_thread_nonrt(joystick, evaluator, config);
  EXPECT_EQ(report.stop_reason, "completed");
  EXPECT_EQ(report.ticks, 50u);
  ASSERT_EQ(joystick.records().size(), 50u);
  for (std::size_t k = 1; k < joystick.records().size(); ++k)
    EXPECT_GT(joystick.records()[k].t_s, joystick.records()[k - 1].t_s);
  // Absolute deadlines: the last tick cannot start before its deadline of 49 ms.
  EXPECT_GE(joystick.records().back().t_s, 0.049);
  EXPECT_GT(report.rate_hz, 0.0);
  EXPECT_GE(report.period_max_us, report.period_p50_us);
}

TEST(ServoThread, BadConfigurationThrowsOnTheCallersThread) {
  const auto program = program_of({});
  PatchEvaluator evaluator(program);
  SimJoystick joystick(sim_device_limits(), HandScript{}, 10);
  ServoConfig config;
  config.rate_hz = 20000;
  EXPECT_THROW(run_servo_thread_nonrt(joystick, evaluator, config), std::invalid_argument);
  EXPECT_EQ(joystick.ticks_played(), 0u);
}

}  // namespace
}  // namespace sandpaper::runtime
