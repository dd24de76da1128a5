// Property: whatever the program and the hand do, no tick commands more than the device maximum,
// and every tick that wanted more is counted as clamped.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"

namespace sandpaper::runtime {
namespace {

using testing::damper;
using testing::grating;
using testing::program_of;
using testing::spring;

constexpr int kTrials = 300;

struct Trial {
  schema::PatchProgram program;
  HandScript script;
  DeviceLimits limits;
};

// `with_damper` false keeps the force a function of position alone, so the test can recompute it.
Trial random_trial(std::mt19937& rng, bool with_damper) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Trial trial;
  trial.limits = sim_device_limits();
  trial.limits.max_force_N = 0.5 + 9.5 * unit(rng);
  std::vector<schema::Term> terms;
  const int count = 1 + static_cast<int>(rng() % 4);
  for (int i = 0; i < count; ++i) {
    switch (rng() % (with_damper ? 3 : 2)) {
      case 0:
        terms.push_back(spring(std::pow(10.0, 1.0 + 4.0 * unit(rng)), 0.04 * (unit(rng) - 0.5), 0.04 * (unit(rng) - 0.5)));
        break;
      case 1: {
        std::vector<float> table(2 + rng() % 64);
        const double amplitude = 40.0 * unit(rng);
        for (float& f : table) f = static_cast<float>(amplitude * (2 * unit(rng) - 1));
        terms.push_back(grating(0.0005 + 0.01 * unit(rng), 6.3 * unit(rng), table));
        break;
      }
      default:
        terms.push_back(damper(500.0 * unit(rng)));
    }
  }
  trial.program = program_of(terms);
  trial.script.path = rng() % 2 ? HandPath::Scan : HandPath::Circle;
  trial.script.speed_m_s = 0.01 + 0.5 * unit(rng);
  trial.script.amplitude_m = 0.001 + 0.06 * unit(rng);
  trial.script.direction_rad = 6.3 * unit(rng);
  return trial;
}

ServoConfig random_config(std::mt19937& rng) {
  ServoConfig config;
  config.rate_hz = 900.0 + static_cast<double>(rng() % 9101);
  config.duration_s = 200.0 / config.rate_hz;
  // No start ramp: these checks compare each tick's force with the law's (SafetyRamp tests the ramp).
  config.ramp_s = 0;
  return config;
}

TEST(ServoClampProperty, NoRecordedForceExceedsTheDeviceMaximum) {
  std::mt19937 rng(20240521);
  std::uint64_t clamped_runs = 0;
  for (int trial_index = 0; trial_index < kTrials; ++trial_index) {
    const Trial trial = random_trial(rng, true);
    const ServoConfig config = random_config(rng);
    PatchEvaluator evaluator(trial.program);
    SimJoystick joystick(trial.limits, trial.script, 256);
    VirtualClock clock;
    const ServoReport report = run_servo_loop(joystick, evaluator, clock, config);
    ASSERT_EQ(report.stop_reason, "completed") << "trial " << trial_index;
    ASSERT_EQ(joystick.records().size(), 200u);
    for (const TickRecord& record : joystick.records())
      ASSERT_LE(std::hypot(record.force_N.x, record.force_N.y), trial.limits.max_force_N)
          << "trial " << trial_index << " t " << record.t_s;
    ASSERT_LE(report.felt_max_lateral_force_N, trial.limits.max_force_N);
    if (report.clamped_ticks > 0) ++clamped_runs;
  }
  // The generator must actually provoke the clamp, or the property says nothing.
  EXPECT_GT(clamped_runs, static_cast<std::uint64_t>(kTrials / 4));
}

// Exactly at most the maximum, not within rounding of it: a 1 GN/m spring pulls far past a 10 N
// device everywhere, and scaling the force down to 10 N used to round to 10.000000000000002 N
// in some directions (issue 16).
TEST(ServoClampProperty, AFarTooStiffSpringIsHeldToExactlyTheMaximum) {
  for (const double max_force_N : {10.0, 7.3, 0.1, 3.0}) {
    DeviceLimits limits = sim_device_limits();
    limits.max_force_N = max_force_N;
    for (const HandPath path : {HandPath::Scan, HandPath::Circle}) {
      HandScript script;
      script.path = path;
      script.speed_m_s = 0.137;
      script.amplitude_m = 0.031;
      script.direction_rad = 0.7;
      const auto program = program_of({spring(1e9, 0.0013, -0.0021)});
      PatchEvaluator evaluator(program);
      SimJoystick joystick(limits, script, 4096);
      VirtualClock clock;
      ServoConfig config;
      config.rate_hz = 1000;
      config.duration_s = 4.0;
      config.ramp_s = 0;
      const ServoReport report = run_servo_loop(joystick, evaluator, clock, config);
      ASSERT_GT(report.clamped_ticks, 3000u);
      for (const TickRecord& record : joystick.records())
        ASSERT_LE(std::hypot(record.force_N.x, record.force_N.y), max_force_N)
            << "exceeds by " << std::hypot(record.force_N.x, record.force_N.y) - max_force_N << " N at t " << record.t_s;
    }
  }
}

TEST(ServoClampProperty, ClampedTicksAreExactlyTheTicksThatWantedTooMuch) {
  std::mt19937 rng(7);
  for (int trial_index = 0; trial_index < kTrials; ++trial_index) {
    const Trial trial = random_trial(rng, false);
    const ServoConfig config = random_config(rng);
    PatchEvaluator evaluator(trial.program);
    SimJoystick joystick(trial.limits, trial.script, 256);
    VirtualClock clock;
    const ServoReport report = run_servo_loop(joystick, evaluator, clock, config);
    std::uint64_t wanted_too_much = 0;
    for (const TickRecord& record : joystick.records()) {
      HandState hand;
      hand.position_m = record.position_m;
      const glm::dvec2 wanted = evaluator.force_rt(hand, 1e-3);
      if (std::hypot(wanted.x, wanted.y) > trial.limits.max_force_N) {
        ++wanted_too_much;
        const double scale = trial.limits.max_force_N / std::hypot(wanted.x, wanted.y);
        ASSERT_NEAR(record.force_N.x, wanted.x * scale, 1e-9) << "trial " << trial_index;
        ASSERT_NEAR(record.force_N.y, wanted.y * scale, 1e-9) << "trial " << trial_index;
      } else {
        ASSERT_EQ(record.force_N, wanted) << "trial " << trial_index;
      }
    }
    ASSERT_EQ(report.clamped_ticks, wanted_too_much) << "trial " << trial_index;
  }
}

}  // namespace
}  // namespace sandpaper::runtime
