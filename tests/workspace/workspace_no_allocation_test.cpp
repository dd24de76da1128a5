// WorkspaceEvaluator::force_rt runs on the servo thread, so it must never allocate: not when the
// hand stays on a patch, not when it crosses into another or onto none (crossfades, patch resets).
// Allocations are counted by tests/support/allocation_counter, as in the servo loop's test.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <new>

#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/runtime/workspace_evaluator.hpp"
#include "allocation_counter.hpp"
#include "workspace_test_support.hpp"

namespace sandpaper::runtime {
namespace {

using sandpaper::test::CountedAllocations;

// A 10 x 10 tiling with gaps between patches (so the hand also crosses onto no patch), patches of
// gratings, springs and dampers, and one big patch in front of part of it.
schema::WorkspaceProgram tiled_workspace() {
  schema::WorkspaceProgram ws;
  ws.size_m[0] = ws.size_m[1] = 0.2;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      schema::PatchProgram p = testws::constant_force_program(0.1 * (i - j));
      schema::GratingTerm g;
      g.period_m = 0.002;
      g.orientation_rad = 0.3 * i;
      for (int k = 0; k < 64; ++k) g.force_N.push_back(static_cast<float>(std::sin(0.1 * k * (j + 1))));
      p.terms.push_back(g);
      schema::SpringTerm s;
      s.stiffness_N_per_m = 10.0 * j;
      p.terms.push_back(s);
      schema::DamperTerm d;
      d.damping_Ns_per_m = 0.1 * i;
      p.terms.push_back(d);
      ws.patches.push_back(testws::placed(std::move(p), -0.09 + 0.02 * i, -0.09 + 0.02 * j, 0.018, 0.018));
    }
  ws.patches.push_back(testws::placed(testws::constant_force_program(0.5), 0.05, 0.05, 0.06, 0.03));
  return ws;
}

TEST(WorkspaceNoAllocation, TheCounterSeesAnAllocation) {
  CountedAllocations counting;
  int* volatile probe = new int(7);
  delete probe;
  EXPECT_EQ(counting.stop(), 1u);
}

TEST(WorkspaceNoAllocation, ForceRtNeverAllocatesAcrossPatchesAndGaps) {
  const auto ws = tiled_workspace();
  WorkspaceEvaluator ev(ws);
  HandState hand;
  std::size_t switches = 0, count = 0;
  {
    CountedAllocations counting;
    ev.reset_rt(hand);
    std::uint32_t last = ev.current_patch();
    for (int k = 0; k < 20000; ++k) {
      const double t = k * 1e-3;
      hand.position_m = {0.095 * std::sin(1.3 * t), 0.095 * std::cos(0.7 * t)};
      hand.velocity_m_s = {0.12 * std::cos(1.3 * t), -0.07 * std::sin(0.7 * t)};
      const glm::dvec2 f = ev.force_rt(hand, 1e-3);
      if (!std::isfinite(f.x)) break;
      switches += ev.current_patch() != last;
      last = ev.current_patch();
    }
    count = counting.stop();
  }
  EXPECT_EQ(count, 0u);
  EXPECT_GT(switches, 50u) << "the path must cross many patch edges for the test to mean anything";
}

// A whole servo run on the sim joystick: allocations must not grow with the number of ticks.
std::size_t allocations_in_run(std::uint64_t ticks) {
  const auto ws = tiled_workspace();
  WorkspaceEvaluator ev(ws);
  SimJoystick joystick(sim_device_limits(), HandScript{HandPath::Circle, 0.1, 0.07, 0.0}, ticks);
  VirtualClock clock;
  ServoConfig config;
  config.rate_hz = 1000;
  config.duration_s = static_cast<double>(ticks) / config.rate_hz;
  std::size_t count = 0;
  std::string stop_reason;
  {
    CountedAllocations counting;
    const ServoReport report = run_servo_loop(joystick, ev, clock, config);
    count = counting.stop();
    stop_reason = report.stop_reason;
  }
  EXPECT_EQ(stop_reason, "completed");
  return count;
}

TEST(WorkspaceNoAllocation, ServoRunAllocationsDoNotGrowWithTicks) {
  const std::size_t short_run = allocations_in_run(1000);
  const std::size_t long_run = allocations_in_run(20000);
  EXPECT_EQ(short_run, long_run);
  EXPECT_LE(short_run, 2u);  // the loop's two timing arrays
}

}  // namespace
}  // namespace sandpaper::runtime
