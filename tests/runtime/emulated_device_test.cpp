// The thesis' joystick emulated on the simulated one (issue 15): positions on 12-bit encoder counts,
// forces in whole joystick units clamped at the largest command, force tables read by sample-and-hold
// (Minsky 1995, Table 2, Table 6, Appendix B 2.1).
#include <cmath>
#include <memory>
#include <set>

#include <gtest/gtest.h>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/emulated_joystick.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"

using namespace sandpaper::runtime;
using namespace sandpaper::runtime::testing;
namespace schema = sandpaper::schema;

namespace {

// calibration/devices/sandpaper-1995.toml.
DeviceQuantization joystick_1995() {
  DeviceQuantization q;
  q.position_step_m = 0.2286 / 4096;
  q.force_step_N[0] = q.force_step_N[1] = 0.00481417274;
  q.command_max = 2048;
  return q;
}

bool on_step(double v, double step) { return std::abs(v / step - std::round(v / step)) < 1e-6; }

}  // namespace

TEST(EmulatedDevice, QuantisesPositionsAndForces) {
  const auto q = joystick_1995();
  const glm::dvec2 p = quantize_position({0.0123456, -0.0311111}, q.position_step_m);
  EXPECT_TRUE(on_step(p.x, q.position_step_m) && on_step(p.y, q.position_step_m));
  EXPECT_LE(std::abs(p.x - 0.0123456), q.position_step_m / 2);
  // 1.926 N is 400.07 joystick units: sent as 400 (Table 8's level 10).
  const glm::dvec2 f = quantize_force({1.926, -0.0024}, q);
  EXPECT_DOUBLE_EQ(f.x, 400 * q.force_step_N[0]);
  EXPECT_DOUBLE_EQ(f.y, 0.0);  // half a unit and less rounds to nothing
  // Clamped at the largest command per axis (2048 ju = 9.86 N), not at 10 N.
  EXPECT_DOUBLE_EQ(quantize_force({20, -20}, q).x, 2048 * q.force_step_N[0]);
  EXPECT_DOUBLE_EQ(quantize_force({20, -20}, q).y, -2048 * q.force_step_N[1]);
  EXPECT_TRUE(std::isnan(quantize_force({NAN, 0}, q).x));  // the loop stops on it
}

TEST(EmulatedDevice, HeldTablesStepFromSampleToSample) {
  // A 4-sample grating of period 4 mm: held, the force is the nearest sample's; interpolated, it ramps.
  const auto program = program_of({grating(0.004, 0, {0.0f, 1.0f, 2.0f, 3.0f})});
  PatchEvaluator held(program, TableSampling::Hold), smooth(program);
  HandState h;
  h.position_m = {0.0014, 0};  // 1.4 samples in
  EXPECT_DOUBLE_EQ(held.force_rt(h, 0).x, 1.0);
  EXPECT_NEAR(smooth.force_rt(h, 0).x, 1.4, 1e-6);
  h.position_m = {0.0036, 0};  // 3.6 samples: nearest is sample 0 of the next period
  EXPECT_DOUBLE_EQ(held.force_rt(h, 0).x, 0.0);
  // A 3 x 2 height field of spacing 1 mm: the nearest sample, zero outside, wrapped when repeated.
  schema::HeightFieldTerm f;
  f.nx = 3;
  f.ny = 2;
  f.spacing_m[0] = f.spacing_m[1] = 0.001;
  f.origin_m[0] = f.origin_m[1] = 0;
  f.force_x_N = {0, 1, 2, 10, 11, 12};
  f.force_y_N = {0, -1, -2, -10, -11, -12};
  auto field = program_of({f});
  field.size_m[0] = field.size_m[1] = 0.01;
  PatchEvaluator held_field(field, TableSampling::Hold);
  h.position_m = {0.0016, 0.0007};  // nearest sample (2, 1)
  EXPECT_DOUBLE_EQ(held_field.force_rt(h, 0).x, 12.0);
  EXPECT_DOUBLE_EQ(held_field.force_rt(h, 0).y, -12.0);
  h.position_m = {0.0024, 0.0};  // past the last sample: outside the field
  EXPECT_DOUBLE_EQ(held_field.force_rt(h, 0).x, 0.0);
  f.repeat = true;
  auto tiled = program_of({f});
  tiled.size_m[0] = tiled.size_m[1] = 0.01;
  PatchEvaluator held_tile(tiled, TableSampling::Hold);
  h.position_m = {0.0031, 0.0009};  // x sample 3 wraps to 0, y sample 1
  EXPECT_DOUBLE_EQ(held_tile.force_rt(h, 0).x, 10.0);
}

// A scan over a fine grating on the emulated joystick: every recorded position is on an encoder count,
// every force a whole number of joystick units, and the force takes only the table's few held values
// (the staircase), where the interpolating device also sends the values between them.
TEST(EmulatedDevice, ScanShowsTheStaircase) {
  std::vector<float> table(256);
  for (std::size_t i = 0; i < table.size(); ++i) table[i] = static_cast<float>(std::round(8 * std::sin(2 * M_PI * static_cast<double>(i) / 256.0)) * 0.2);
  const auto program = program_of({grating(0.0025, 0, table)});
  const auto q = joystick_1995();
  const HandScript script{HandPath::Scan, 0.05, 0.03, 0};
  ServoConfig config;
  config.rate_hz = 900;
  config.duration_s = 1.0;
  config.ramp_s = 0;

  EmulatedJoystick emulated(std::make_unique<SimJoystick>(sim_device_limits(), script, 0), {q, TableSampling::Hold}, 1000);
  // The device describes its emulation; the loop takes its command steps from it.
  EXPECT_EQ(emulated.table_sampling(), TableSampling::Hold);
  EXPECT_DOUBLE_EQ(emulated.command_quantum().step_N[1], q.force_step_N[1]);
  EXPECT_EQ(emulated.command_quantum().max_steps, 2048);
  PatchEvaluator held(program, emulated.table_sampling());
  VirtualClock clock;
  TelemetryRing ring(1000);
  ServoConfig emulated_config = config;
  emulated_config.ramp_s = 0.05;  // the loop rounds after its ramp: still whole units
  emulated_config.telemetry = &ring;
  ASSERT_EQ(run_servo_loop(emulated, held, clock, emulated_config).stop_reason, "completed");
  std::set<double> forces;
  for (const auto& t : emulated.records()) {
    ASSERT_TRUE(on_step(t.position_m.x, q.position_step_m)) << t.position_m.x;
    ASSERT_TRUE(on_step(t.force_N.x, q.force_step_N[0])) << t.force_N.x;
    if (t.t_s >= 0.05) forces.insert(t.force_N.x);
  }
  // What the loop reports sending is what the device took: whole units, though nobody told the loop.
  TelemetryRecord r;
  std::size_t reported = 0;
  while (ring.pop_nonrt(r)) {
    ++reported;
    ASSERT_TRUE(on_step(r.force_N.x, q.force_step_N[0])) << r.force_N.x;
  }
  EXPECT_GE(reported, 899u);
  ASSERT_GE(emulated.records().size(), 899u);
  EXPECT_LE(forces.size(), 17u);  // the table's 17 levels (-8 .. 8 x 0.2 N), no in-between values

  SimJoystick plain(sim_device_limits(), script, 1000);
  PatchEvaluator smooth(program);
  VirtualClock clock2;
  ASSERT_EQ(run_servo_loop(plain, smooth, clock2, config).stop_reason, "completed");
  std::set<double> smooth_forces;
  for (const auto& t : plain.records()) smooth_forces.insert(t.force_N.x);
  EXPECT_GT(smooth_forces.size(), forces.size() + 10);  // interpolation: values between the levels
}

TEST(EmulatedDevice, ACommandStepThatIsNotAForceIsRefusedBeforeTheFirstTick) {
  const auto program = program_of({grating(0.0025, 0, std::vector<float>(256, 1.0f))});
  ServoConfig config;
  config.rate_hz = 900;
  config.duration_s = 0.1;
  for (const double bad : {std::nan(""), static_cast<double>(INFINITY), -0.01}) {
    auto q = joystick_1995();
    q.force_step_N[1] = bad;
    EmulatedJoystick device(std::make_unique<SimJoystick>(sim_device_limits(), HandScript{}, 0), {q}, 100);
    PatchEvaluator evaluator(program);
    VirtualClock clock;
    try {
      run_servo_loop(device, evaluator, clock, config);
      ADD_FAILURE() << "a command step of " << bad << " N played";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("command step"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("axis y"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(device.records().empty()) << "no tick ran";
  }
}
