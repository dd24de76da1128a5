// A 1,000-patch workspace written as a .hws file, compiled, and played on the simulated joystick
// with the virtual clock. Each tick's force is checked against the patch under the hand evaluated
// on its own (a separate PatchEvaluator at the position relative to that patch's centre).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <fmt/format.h>

#include "sandpaper/compiler/workspace.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/runtime/workspace_evaluator.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {

namespace fs = std::filesystem;

// 40 columns x 25 rows on the default 228.6 mm workspace; each patch 5 mm x 8 mm in its cell.
fs::path write_thousand_patches() {
  const fs::path dir = test::temp_dir("ws-1000");
  const char* materials[] = {"corduroy", "a10p25", "denim-twill", "grating period 2 mm amplitude 1 N",
                             "grating period 4 mm orientation 90 deg; roughness 0.2"};
  std::ofstream out(dir / "thousand.hws");
  out << "workspace \"thousand\" {\n";
  const double side = 228.6, cw = side / 40, ch = side / 25;
  int k = 0;
  for (int row = 0; row < 25; ++row)
    for (int col = 0; col < 40; ++col, ++k)
      out << fmt::format("  patch \"{}\" at {:.4f} mm, {:.4f} mm size 5 mm x 8 mm\n", materials[k % 5],
                         -side / 2 + (col + 0.5) * cw, -side / 2 + (row + 0.5) * ch);
  out << "}\n";
  return dir / "thousand.hws";
}

TEST(LargeWorkspace, AThousandPatchesCompileAndPlay) {
  auto r = compiler::compile_workspace_file(test::shipped_compiler(), write_thousand_patches());
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const auto& ws = *r.program;
  ASSERT_EQ(ws.patches.size(), 1000u);
  EXPECT_EQ(ws.patches[999].source, "grating period 4 mm orientation 90 deg; roughness 0.2");

  runtime::WorkspaceEvaluator ev(ws);
  EXPECT_LE(ev.grid().max_cell_entries(), 4u);
  // A diagonal scan at 100 mm/s across most of the workspace, 1 kHz, 3 s.
  runtime::HandScript scan{runtime::HandPath::Scan, 0.1, 0.1, 0.6};
  runtime::ServoConfig cfg;
  cfg.rate_hz = 1000;
  cfg.duration_s = 3.0;
  // No start ramp: these checks compare each tick's force with the law's (SafetyRamp tests the ramp).
  cfg.ramp_s = 0;
  runtime::SimJoystick sim(runtime::sim_device_limits(), scan, 3000);
  runtime::VirtualClock clock;
  const auto rep = runtime::run_servo_loop(sim, ev, clock, cfg);
  ASSERT_EQ(rep.stop_reason, "completed");
  ASSERT_EQ(rep.ticks, 3000u);

  // Independent evaluators for every patch, fed relative positions.
  std::vector<std::unique_ptr<runtime::PatchEvaluator>> alone;
  for (const auto& p : ws.patches) alone.push_back(std::make_unique<runtime::PatchEvaluator>(*p.program));
  std::set<std::uint32_t> touched;
  std::size_t compared = 0, gaps = 0;
  const auto& recs = sim.records();
  for (std::size_t i = 0; i < recs.size(); ++i) {
    const glm::dvec2 p = recs[i].position_m;
    // Which patch is under the hand, by the definition: the last one whose rectangle holds p.
    std::uint32_t under = runtime::WorkspaceEvaluator::kNoPatch;
    for (std::size_t k = ws.patches.size(); k-- > 0;) {
      const auto& q = ws.patches[k];
      if (std::abs(p.x - q.centre_m[0]) <= 0.5 * q.size_m[0] && std::abs(p.y - q.centre_m[1]) <= 0.5 * q.size_m[1]) {
        under = static_cast<std::uint32_t>(k);
        break;
      }
    }
    // Skip ticks within the crossfade after a change of patch (the last 3 ticks' patches must agree).
    bool settled = i >= 3;
    for (std::size_t b = 1; settled && b <= 3; ++b) settled = ev.patch_at(recs[i - b].position_m) == under;
    if (under == runtime::WorkspaceEvaluator::kNoPatch) {
      ++gaps;
      if (settled) {
        EXPECT_EQ(recs[i].force_N.x, 0.0) << "tick " << i;
        EXPECT_EQ(recs[i].force_N.y, 0.0) << "tick " << i;
      }
      continue;
    }
    touched.insert(under);
    if (!settled) continue;
    runtime::HandState h;
    h.position_m = p - glm::dvec2{ws.patches[under].centre_m[0], ws.patches[under].centre_m[1]};
    const glm::dvec2 expected = alone[under]->force_rt(h, 1e-3);
    // The loop's velocity filter feeds the damper-free gratings nothing, so positions decide the force.
    EXPECT_NEAR(recs[i].force_N.x, expected.x, 1e-9) << "tick " << i << " patch " << under;
    EXPECT_NEAR(recs[i].force_N.y, expected.y, 1e-9) << "tick " << i << " patch " << under;
    ++compared;
  }
  EXPECT_GE(touched.size(), 30u);
  EXPECT_GT(compared, 1000u);
  EXPECT_GT(gaps, 100u);
  EXPECT_GT(rep.felt_max_lateral_force_N, 0.5);
}

}  // namespace
}  // namespace sandpaper
