// Closing the loop: a roughness target, compiled and played by a scripted lateral scan on the
// simulated joystick, gives back the target's maximum lateral force (within 2 %) and the
// roughness predicted from the measured force (within 0.02). Virtual clock: deterministic.
#include <algorithm>
#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "test_support.hpp"

using namespace sandpaper;

namespace {

// Issue 2's ratio scale restated independently of the calibration code: roughness 1 is 382 gf.
double target_force(double r) { return 382 * 9.80665e-3 * std::pow(r, 1 / 0.76); }
double roughness_from(double f) { return std::pow(f / (382 * 9.80665e-3), 0.76); }

struct Played {
  runtime::ServoReport report;
  std::vector<runtime::TickRecord> records;
};

Played play(const schema::PatchProgram& p, runtime::HandScript script, double duration_s, double rate_hz = 1000) {
  runtime::ServoConfig cfg;
  cfg.rate_hz = rate_hz;
  cfg.duration_s = duration_s;
  auto ticks = static_cast<std::size_t>(std::llround(duration_s * rate_hz));
  runtime::SimJoystick sim(runtime::sim_device_limits(), script, ticks);
  runtime::PatchEvaluator ev(p);
  runtime::VirtualClock clock;
  Played out{runtime::run_servo_loop(sim, ev, clock, cfg), {}};
  out.records = sim.records();
  return out;
}

}  // namespace

class ClosedLoop : public ::testing::TestWithParam<std::tuple<double, double>> {};

TEST_P(ClosedLoop, ScanMeasuresTheTargetForceAndRoughness) {
  auto [roughness, period_mm] = GetParam();
  std::ostringstream src;
  src << "grating period " << period_mm << " mm hill 50%; roughness " << roughness;
  auto r = test::shipped_compiler().compile_text(src.str());
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);

  // A slow scan (5 mm/s, 5 um per tick at 1 kHz) so that the narrowest force peaks, at 0.7 mm
  // (Gaussian wall sigma 16 um), are sampled near their top; it crosses at least two periods.
  runtime::HandScript scan;
  scan.path = runtime::HandPath::Scan;
  scan.speed_m_s = 0.005;
  scan.amplitude_m = std::max(0.002, 1.2e-3 * period_mm);
  auto played = play(*r.program, scan, 6.0);
  ASSERT_EQ(played.report.stop_reason, "completed");
  ASSERT_EQ(played.report.ticks, 6000u);

  double target = target_force(roughness);
  double measured = played.report.felt_max_lateral_force_N;
  EXPECT_NEAR(measured, target, 0.02 * target) << src.str();
  EXPECT_NEAR(roughness_from(measured), roughness, 0.02) << src.str();
  // The measured force is the largest force actually sent, tick by tick.
  double largest = 0;
  for (const auto& t : played.records) largest = std::max(largest, std::hypot(t.force_N.x, t.force_N.y));
  EXPECT_DOUBLE_EQ(largest, measured);
}

INSTANTIATE_TEST_SUITE_P(CalibratedRange, ClosedLoop,
                         ::testing::Combine(::testing::Values(0.1, 0.2, 0.35, 0.5, 0.75, 1.0),
                                            ::testing::Values(0.7, 2.5, 10.0)));

TEST(ClosedLoopLibrary, LibraryCorduroyOnACircle) {
  auto r = test::shipped_compiler().compile_text("corduroy");
  ASSERT_TRUE(r.ok());
  runtime::HandScript circle;
  circle.path = runtime::HandPath::Circle;
  circle.speed_m_s = 0.01;
  circle.amplitude_m = 0.02;
  auto played = play(*r.program, circle, 8.0);
  // A circle crosses the ribs at every angle; where it runs across them the peak is reached.
  EXPECT_NEAR(played.report.felt_max_lateral_force_N, target_force(0.45), 0.02 * target_force(0.45));
  EXPECT_EQ(played.report.clamped_ticks, 0u);
}

TEST(ClosedLoopLibrary, RealPhotographStaysUnderItsCompiledMaximumInside) {
  auto r = test::shipped_compiler().compile_file(std::string(SANDPAPER_SOURCE_DIR) + "/examples/gravel.hmat");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  runtime::HandScript scan;
  scan.speed_m_s = 0.02;
  scan.amplitude_m = 0.03;  // inside the 80 mm patch, away from its rim
  auto played = play(*r.program, scan, 5.0);
  EXPECT_EQ(played.report.stop_reason, "completed");
  // Bilinear interpolation never exceeds the field's samples, whose maximum inside the rim is the target.
  EXPECT_LE(played.report.felt_max_lateral_force_N, r.program->max_lateral_force_N * (1 + 1e-6));
  EXPECT_GT(played.report.felt_max_lateral_force_N, 0.3 * r.program->max_lateral_force_N);
}

TEST(ClosedLoopLibrary, ForceIsSpatialNotTemporal) {
  // The same scan at two servo rates passes the same places: the peak force agrees.
  auto r = test::shipped_compiler().compile_text("a10p25");
  ASSERT_TRUE(r.ok());
  runtime::HandScript scan;
  scan.speed_m_s = 0.005;
  scan.amplitude_m = 0.004;
  auto a = play(*r.program, scan, 4.0, 1000);
  auto b = play(*r.program, scan, 4.0, 4000);
  EXPECT_EQ(b.report.ticks, 4 * a.report.ticks);
  EXPECT_NEAR(a.report.felt_max_lateral_force_N, b.report.felt_max_lateral_force_N, 0.01 * b.report.felt_max_lateral_force_N);
  EXPECT_NEAR(b.report.felt_max_lateral_force_N, 400 * 0.490909 * 0.00980665, 0.005);  // a10p25: 400 ju (Table 8)
}

// `bumpiness 0.6` is a grating whose period the bumpiness-provisional map gives: 10 mm x 0.6^2 =
// 3.6 mm, restated from the map file's law. A slow scan finds the walls that push the hand one way
// (force x above half its peak) and measures how far apart they lie.
TEST(ClosedLoopPercepts, BumpinessPlaysItsSpatialPeriod) {
  auto r = test::shipped_compiler().compile_text("bumpiness 0.6; roughness 0.4");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  runtime::HandScript scan;
  scan.path = runtime::HandPath::Scan;
  scan.speed_m_s = 0.005;
  scan.amplitude_m = 0.009;
  auto played = play(*r.program, scan, 8.0);
  ASSERT_EQ(played.report.stop_reason, "completed");
  const double peak = played.report.felt_max_lateral_force_N;
  ASSERT_GT(peak, 0);
  // Centres of the runs of ticks with F_x > peak / 2 while the hand moves toward +x.
  std::vector<double> centres;
  double sum = 0;
  int n = 0;
  for (std::size_t k = 1; k < played.records.size(); ++k) {
    const auto& t = played.records[k];
    const bool in = t.force_N.x > 0.5 * peak && t.position_m.x > played.records[k - 1].position_m.x;
    if (in) sum += t.position_m.x, ++n;
    else if (n > 0) centres.push_back(sum / n), sum = 0, n = 0;
  }
  std::sort(centres.begin(), centres.end());
  std::vector<double> walls;  // the same wall met on several sweeps is one wall
  for (double c : centres)
    if (walls.empty() || c - walls.back() > 0.5e-3) walls.push_back(c);
  ASSERT_GE(walls.size(), 4u);
  for (std::size_t i = 1; i < walls.size(); ++i) EXPECT_NEAR(walls[i] - walls[i - 1], 0.0036, 0.02e-3) << "wall " << i;
}
