// The replay device: a run recorded to the trace CSV (`sandpaper run --trace`) and played back
// through ReplayJoystick on the virtual clock gives the same force, bit for bit, on every tick.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/runtime/dynamic_hand.hpp"
#include "sandpaper/runtime/replay_joystick.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/trace_csv.hpp"
#include "test_support.hpp"

using namespace sandpaper;

namespace {

std::vector<glm::dvec2> positions_of(const std::vector<runtime::TickRecord>& trace) {
  std::vector<glm::dvec2> p;
  for (const auto& t : trace) p.push_back(t.position_m);
  return p;
}

std::vector<runtime::TickRecord> replay(const schema::PatchProgram& program, const std::vector<runtime::TickRecord>& trace,
                                        double rate_hz, runtime::ServoReport* report = nullptr) {
  runtime::ReplayJoystick device(runtime::sim_device_limits(), positions_of(trace));
  runtime::PatchEvaluator ev(program);
  runtime::VirtualClock clock;
  runtime::ServoConfig cfg;
  cfg.rate_hz = rate_hz;
  cfg.duration_s = static_cast<double>(trace.size()) / rate_hz;
  auto rep = runtime::run_servo_loop(device, ev, clock, cfg);
  if (report) *report = rep;
  return device.records();
}

// Textures, a stateful mass and an energy-bounded term together: every kind of state must replay.
const char* kMaterial =
    "grating period 2.5 mm; roughness 0.5; physics Mass mass 50 g stiffness 100 N/m friction 0.1 N*s/m; "
    "force AntiViscous damping 2 N*s/m; energy budget 5 mJ refill 2 mW";

TEST(Replay, ARecordedTraceReplaysToTheSameForcesBitForBit) {
  auto r = test::shipped_compiler().compile_text(kMaterial);
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  for (double rate : {900.0, 1000.0}) {
    // Recorded on the dynamic hand, so the positions are not the scripted path's own.
    runtime::HandScript circle;
    circle.path = runtime::HandPath::Circle;
    circle.amplitude_m = 0.02;
    circle.speed_m_s = 0.08;
    runtime::ServoConfig cfg;
    cfg.rate_hz = rate;
    cfg.duration_s = 2;
    const auto n = static_cast<std::size_t>(std::llround(2 * rate));
    runtime::DynamicHandJoystick hand(runtime::sim_device_limits(), circle, {}, n);
    runtime::PatchEvaluator ev(*r.program);
    runtime::VirtualClock clock;
    ASSERT_EQ(runtime::run_servo_loop(hand, ev, clock, cfg).stop_reason, "completed");

    // Through the file format, as `sandpaper run --trace` then `--replay` would.
    const auto trace = runtime::parse_trace_csv(runtime::format_trace_csv(hand.records()));
    ASSERT_EQ(trace.size(), n);
    runtime::ServoReport rep;
    const auto again = replay(*r.program, trace, rate, &rep);
    EXPECT_EQ(rep.stop_reason, "completed");
    ASSERT_EQ(again.size(), n);
    std::size_t differing = 0;
    double biggest = 0;
    for (std::size_t k = 0; k < n; ++k) {
      EXPECT_EQ(again[k].t_s, trace[k].t_s);
      EXPECT_EQ(again[k].position_m, trace[k].position_m);
      differing += again[k].force_N != trace[k].force_N;
      biggest = std::max(biggest, std::hypot(trace[k].force_N.x, trace[k].force_N.y));
    }
    EXPECT_EQ(differing, 0u) << rate << " Hz";
    EXPECT_GT(biggest, 0.1);  // the material pushed: the comparison is not of zeros
  }
}

TEST(Replay, ADifferentMaterialOnTheSameTraceGivesDifferentForces) {
  // The replay really evaluates the program (it does not echo the recorded forces).
  auto a = test::shipped_compiler().compile_text("grating period 2.5 mm; roughness 0.5");
  auto b = test::shipped_compiler().compile_text("grating period 2.5 mm; roughness 0.6");
  ASSERT_TRUE(a.ok() && b.ok());
  runtime::SimJoystick sim(runtime::sim_device_limits(), {}, 1000);
  runtime::PatchEvaluator ev(*a.program);
  runtime::VirtualClock clock;
  runtime::ServoConfig cfg;
  cfg.duration_s = 1;
  runtime::run_servo_loop(sim, ev, clock, cfg);
  const auto other = replay(*b.program, sim.records(), 1000);
  ASSERT_EQ(other.size(), sim.records().size());
  std::size_t differing = 0;
  for (std::size_t k = 0; k < other.size(); ++k) differing += other[k].force_N != sim.records()[k].force_N;
  EXPECT_GT(differing, 100u);
}

TEST(Replay, ARunLongerThanTheRecordingStopsWithAFailedRead) {
  std::vector<runtime::TickRecord> trace(10, runtime::TickRecord{0, {0.001, 0}, {0, 0}});
  runtime::ReplayJoystick device(runtime::sim_device_limits(), positions_of(trace));
  schema::PatchProgram p;
  runtime::PatchEvaluator ev(p);
  runtime::VirtualClock clock;
  runtime::ServoConfig cfg;
  cfg.duration_s = 0.02;
  const auto rep = runtime::run_servo_loop(device, ev, clock, cfg);
  EXPECT_EQ(rep.stop_reason, "device read failed");
  EXPECT_EQ(device.records().size(), 10u);
}

TEST(TraceCsv, ReadsBackTheSameDoublesAndRejectsBadRows) {
  std::vector<runtime::TickRecord> recs{{0.001, {0.1 / 3, -2e-7}, {1.0 / 7, 3.14159265358979}}};
  const auto back = runtime::parse_trace_csv(runtime::format_trace_csv(recs));
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].position_m, recs[0].position_m);
  EXPECT_EQ(back[0].force_N, recs[0].force_N);
  EXPECT_THROW(runtime::parse_trace_csv("t,x\n"), std::invalid_argument);
  EXPECT_THROW(runtime::parse_trace_csv("t_s,x_m,y_m,force_x_N,force_y_N\n0,1,2,3\n"), std::invalid_argument);
  EXPECT_THROW(runtime::parse_trace_csv("t_s,x_m,y_m,force_x_N,force_y_N\n0,1,2,3,nan\n"), std::invalid_argument);
  // Older traces, written with 9 digits and CRLF line ends, still read.
  EXPECT_EQ(runtime::parse_trace_csv("t_s,x_m,y_m,force_x_N,force_y_N\r\n0.001,0.5,0,1,2\r\n").size(), 1u);
}

}  // namespace
