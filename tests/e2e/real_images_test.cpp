// Real photographs (library/images, CC0) compiled from the examples and played on the simulated
// joystick: a hand circling inside the patch feels forces up to, never above, the compiled maximum.
#include <cmath>

#include <gtest/gtest.h>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "test_support.hpp"

using namespace sandpaper;

class RealImages : public ::testing::TestWithParam<const char*> {};

TEST_P(RealImages, PlayOnTheSimulatedJoystick) {
  auto r = test::shipped_compiler().compile_file(std::string(SANDPAPER_SOURCE_DIR) + "/" + GetParam());
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  runtime::HandScript circle;
  circle.path = runtime::HandPath::Circle;
  circle.speed_m_s = 0.02;
  circle.amplitude_m = 0.03;  // inside the 90-100 mm patches, away from their rims
  runtime::ServoConfig cfg;
  cfg.rate_hz = 1000;
  cfg.duration_s = 5.0;
  runtime::SimJoystick sim(runtime::sim_device_limits(), circle, 5000);
  runtime::PatchEvaluator ev(*r.program);
  runtime::VirtualClock clock;
  auto report = runtime::run_servo_loop(sim, ev, clock, cfg);
  EXPECT_EQ(report.stop_reason, "completed");
  EXPECT_EQ(report.ticks, 5000u);
  EXPECT_EQ(report.clamped_ticks, 0u);
  // Bilinear sampling never exceeds the field's samples, whose largest inside the rim is the maximum.
  EXPECT_LE(report.felt_max_lateral_force_N, r.program->max_lateral_force_N * (1 + 1e-6));
  EXPECT_GT(report.felt_max_lateral_force_N, 0.3 * r.program->max_lateral_force_N);
  // A textured surface: the force changes direction along the path, not a constant push.
  double sum_x = 0, sum_abs = 0;
  for (const auto& t : sim.records()) {
    sum_x += t.force_N.x;
    sum_abs += std::abs(t.force_N.x);
  }
  EXPECT_LT(std::abs(sum_x), 0.5 * sum_abs);
}

INSTANTIATE_TEST_SUITE_P(Examples, RealImages,
                         ::testing::Values("examples/brick-relief.hmat", "examples/grass.hmat", "examples/gravel.hmat"));
