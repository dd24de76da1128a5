// WorkspaceEvaluator: positions relative to the patch centre, the frontmost patch wins, and a
// crossfade keeps patch boundaries from stepping the force by more than the patches' own forces.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/runtime/workspace_evaluator.hpp"
#include "workspace_test_support.hpp"

namespace sandpaper::runtime {
namespace {

using testws::constant_force_program;
using testws::placed;

HandState at(double x, double y, glm::dvec2 v = {0, 0}) {
  HandState h;
  h.position_m = {x, y};
  h.velocity_m_s = v;
  return h;
}

schema::PatchProgram spring_program(double k) {
  schema::PatchProgram p;
  schema::SpringTerm s;
  s.stiffness_N_per_m = k;
  p.terms.push_back(s);
  return p;
}

schema::PatchProgram damper_program(double b) {
  schema::PatchProgram p;
  schema::DamperTerm d;
  d.damping_Ns_per_m = b;
  p.terms.push_back(d);
  return p;
}

TEST(WorkspaceEvaluator, PositionsAreRelativeToThePatchCentre) {
  schema::WorkspaceProgram ws;
  ws.patches.push_back(placed(spring_program(200), 0.03, 0.01, 0.04, 0.04));
  WorkspaceEvaluator ev(ws, 0.0);
  ev.reset_rt(at(0.035, 0.012));
  // F = -k (p - c): the spring pulls toward the patch's own centre, not the workspace's.
  const glm::dvec2 f = ev.force_rt(at(0.035, 0.012), 1e-3);
  EXPECT_NEAR(f.x, -200 * 0.005, 1e-12);
  EXPECT_NEAR(f.y, -200 * 0.002, 1e-12);
  EXPECT_EQ(ev.current_patch(), 0u);
}

TEST(WorkspaceEvaluator, VelocityPassesUnchanged) {
  schema::WorkspaceProgram ws;
  ws.patches.push_back(placed(damper_program(3), -0.05, 0.0, 0.02, 0.02));
  WorkspaceEvaluator ev(ws, 0.0);
  ev.reset_rt(at(-0.05, 0.0));
  const glm::dvec2 f = ev.force_rt(at(-0.05, 0.0, {0.1, -0.2}), 1e-3);
  EXPECT_NEAR(f.x, -0.3, 1e-12);
  EXPECT_NEAR(f.y, 0.6, 1e-12);
}

TEST(WorkspaceEvaluator, TheFrontmostPatchAloneSendsForce) {
  schema::WorkspaceProgram ws;
  ws.patches.push_back(placed(constant_force_program(1.0), 0.0, 0.0, 0.06, 0.06));   // back
  ws.patches.push_back(placed(constant_force_program(-2.0), 0.02, 0.0, 0.04, 0.04));  // front, overlapping
  WorkspaceEvaluator ev(ws, 0.0);
  ev.reset_rt(at(0, 0));
  EXPECT_DOUBLE_EQ(ev.force_rt(at(-0.025, 0), 1e-3).x, 1.0);   // the back patch only
  EXPECT_DOUBLE_EQ(ev.force_rt(at(0.01, 0), 1e-3).x, -2.0);    // both: the front one, not the sum
  EXPECT_DOUBLE_EQ(ev.force_rt(at(0.035, 0), 1e-3).x, -2.0);   // the front one only
  EXPECT_DOUBLE_EQ(ev.force_rt(at(0.09, 0), 1e-3).x, 0.0);     // none
  EXPECT_EQ(ev.current_patch(), WorkspaceEvaluator::kNoPatch);
}

TEST(WorkspaceEvaluator, CrossfadeIsLinearOverItsTime) {
  schema::WorkspaceProgram ws;
  ws.patches.push_back(placed(constant_force_program(1.0), -0.02, 0.0, 0.04, 0.04));
  ws.patches.push_back(placed(constant_force_program(-3.0), 0.02, 0.0, 0.04, 0.04));
  WorkspaceEvaluator ev(ws, 0.002);
  ev.reset_rt(at(-0.01, 0));
  EXPECT_DOUBLE_EQ(ev.force_rt(at(-0.01, 0), 5e-4).x, 1.0);
  // Crossing at 0.5 ms ticks: the force moves a quarter of the way each tick, then holds.
  for (int k = 1; k <= 4; ++k) EXPECT_NEAR(ev.force_rt(at(0.01, 0), 5e-4).x, 1.0 + (k / 4.0) * (-3.0 - 1.0), 1e-12) << k;
  EXPECT_DOUBLE_EQ(ev.force_rt(at(0.01, 0), 5e-4).x, -3.0);
  // Leaving to no patch fades to zero the same way.
  EXPECT_NEAR(ev.force_rt(at(0.05, 0.05), 1e-3).x, -1.5, 1e-12);
  EXPECT_NEAR(ev.force_rt(at(0.05, 0.05), 1e-3).x, 0.0, 1e-12);
}

TEST(WorkspaceEvaluator, TurningBackMidFadeStartsFromTheForceSent) {
  schema::WorkspaceProgram ws;
  ws.patches.push_back(placed(constant_force_program(2.0), -0.02, 0.0, 0.04, 0.04));
  ws.patches.push_back(placed(constant_force_program(-2.0), 0.02, 0.0, 0.04, 0.04));
  WorkspaceEvaluator ev(ws, 0.004);
  ev.reset_rt(at(-0.01, 0));
  EXPECT_DOUBLE_EQ(ev.force_rt(at(-0.01, 0), 1e-3).x, 2.0);
  EXPECT_NEAR(ev.force_rt(at(0.01, 0), 1e-3).x, 1.0, 1e-12);   // a quarter of the way to -2
  // Back onto the first patch: from 1.0 toward 2.0, not a jump to either end.
  EXPECT_NEAR(ev.force_rt(at(-0.01, 0), 1e-3).x, 1.25, 1e-12);
}

// Plays a scan across two adjacent patches with opposite constant forces on the sim joystick and
// returns the largest tick-to-tick change of the force.
double largest_step(double crossfade_s, double rate_hz, double f_left, double f_right) {
  schema::WorkspaceProgram ws;
  ws.patches.push_back(placed(constant_force_program(f_left), -0.02, 0.0, 0.04, 0.04));
  ws.patches.push_back(placed(constant_force_program(f_right), 0.02, 0.0, 0.04, 0.04));
  WorkspaceEvaluator ev(ws, crossfade_s);
  HandScript scan{HandPath::Scan, 0.08, 0.035, 0.0};  // crosses the shared edge at x = 0 several times
  ServoConfig cfg;
  cfg.rate_hz = rate_hz;
  cfg.duration_s = 4.0;
  const auto ticks = static_cast<std::size_t>(std::llround(cfg.duration_s * rate_hz));
  SimJoystick sim(sim_device_limits(), scan, ticks);
  VirtualClock clock;
  const ServoReport rep = run_servo_loop(sim, ev, clock, cfg);
  EXPECT_EQ(rep.stop_reason, "completed");
  double step = 0;
  const auto& recs = sim.records();
  EXPECT_EQ(recs.size(), ticks);
  int crossings = 0;
  for (std::size_t i = 1; i < recs.size(); ++i) {
    step = std::max(step, std::abs(recs[i].force_N.x - recs[i - 1].force_N.x));
    crossings += (recs[i].position_m.x > 0) != (recs[i - 1].position_m.x > 0);
  }
  EXPECT_GE(crossings, 4);
  // Away from the edge each patch's own force is felt in full.
  for (const auto& r : recs) {
    if (r.t_s < 0.01) continue;
    if (r.position_m.x < -0.005) {
      EXPECT_DOUBLE_EQ(r.force_N.x, f_left);
    } else if (r.position_m.x > 0.005) {
      EXPECT_DOUBLE_EQ(r.force_N.x, f_right);
    }
  }
  return step;
}

TEST(WorkspaceEvaluator, BoundaryStepsStayWithinThePatchesOwnForces) {
  const double f_left = 1.5, f_right = -2.5;
  const double bound = std::max(std::abs(f_left), std::abs(f_right));
  for (double rate : {900.0, 1000.0, 4000.0}) {
    SCOPED_TRACE(rate);
    EXPECT_LE(largest_step(WorkspaceEvaluator::kDefaultCrossfade_s, rate, f_left, f_right), bound + 1e-12);
  }
  // Without the crossfade the force jumps by the sum, which is what the test must be able to see.
  EXPECT_NEAR(largest_step(0.0, 1000.0, f_left, f_right), std::abs(f_left - f_right), 1e-12);
}

TEST(WorkspaceEvaluator, NonFinitePositionIsAFault) {
  schema::WorkspaceProgram ws;
  ws.patches.push_back(placed(constant_force_program(1.0), 0, 0, 0.04, 0.04));
  WorkspaceEvaluator ev(ws);
  ev.reset_rt(at(0, 0));
  const glm::dvec2 f = ev.force_rt(at(std::numeric_limits<double>::quiet_NaN(), 0), 1e-3);
  EXPECT_TRUE(std::isnan(f.x) && std::isnan(f.y));
}

TEST(WorkspaceEvaluator, RefusesInconsistentWorkspaces) {
  schema::WorkspaceProgram ws;
  ws.patches.push_back(placed(constant_force_program(1.0), 0, 0, 0.04, 0.04));
  EXPECT_THROW(WorkspaceEvaluator(ws, -1e-3), std::invalid_argument);
  auto wider = *ws.patches[0].program;
  wider.size_m[0] = 0.05;  // placed and program sizes disagree
  ws.patches[0].program = std::make_shared<const schema::PatchProgram>(wider);
  EXPECT_THROW(WorkspaceEvaluator{ws}, std::invalid_argument);
  ws.patches[0] = placed(constant_force_program(1.0), 0, 0, 0.0, 0.04);
  EXPECT_THROW(WorkspaceEvaluator{ws}, std::invalid_argument);
  schema::GratingTerm broken;  // period 0: PatchEvaluator refuses it, and the message names the patch
  ws.patches[0] = placed(constant_force_program(1.0), 0, 0, 0.04, 0.04, "broken-one");
  auto with_broken = *ws.patches[0].program;
  with_broken.terms = {broken};
  ws.patches[0].program = std::make_shared<const schema::PatchProgram>(with_broken);
  try {
    WorkspaceEvaluator ev(ws);
    ADD_FAILURE() << "a broken patch program was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("broken-one"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sandpaper::runtime
