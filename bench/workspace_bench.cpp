// Cost of one WorkspaceEvaluator::force_rt tick as the workspace grows from 1 to 1,000 patches:
// the frontmost-patch lookup (uniform grid, one cell's list) plus one patch's grating. The hand
// wanders over the whole workspace, crossing patch edges and gaps, so crossfades and patch resets
// are part of the measured cost. Results as JSON: --benchmark_out=FILE (JSON is the default format).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "sandpaper/runtime/workspace_evaluator.hpp"

namespace sandpaper::runtime {
namespace {

// `n` patches tiling the 228.6 mm workspace (thesis Table 2) on a near-square lattice, each 90 % of
// its cell, each a 256-sample grating of its own period and orientation.
schema::WorkspaceProgram tiled(int n) {
  schema::WorkspaceProgram ws;
  const double side = ws.size_m[0];
  const int cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  const int rows = (n + cols - 1) / cols;
  const double cw = side / cols, ch = side / rows;
  for (int k = 0; k < n; ++k) {
    schema::PatchProgram p;
    schema::GratingTerm g;
    g.period_m = 0.001 + 0.0001 * (k % 50);
    g.orientation_rad = 0.1 * (k % 31);
    for (int i = 0; i < 256; ++i) g.force_N.push_back(static_cast<float>(std::sin(6.283185307179586 * i / 256.0)));
    p.terms.push_back(g);
    const double centre[2] = {-side / 2 + (k % cols + 0.5) * cw, -side / 2 + (k / cols + 0.5) * ch};
    const double size[2] = {0.9 * cw, 0.9 * ch};
    ws.patches.push_back(schema::place_patch(std::move(p), centre, size, "bench"));
  }
  return ws;
}

// The hand's path, sampled once so that the loop measures the tick and not the trigonometry: a
// Lissajous figure over the workspace at 1 kHz, 65,536 ticks long.
const std::vector<glm::dvec2>& hand_path() {
  static const std::vector<glm::dvec2> path = [] {
    std::vector<glm::dvec2> p(1 << 16);
    for (std::size_t k = 0; k < p.size(); ++k) {
      const double t = 1e-3 * static_cast<double>(k);
      p[k] = {0.11 * std::sin(t * 1.3), 0.11 * std::cos(t * 0.7)};
    }
    return p;
  }();
  return path;
}

void BM_WorkspaceTick(benchmark::State& state) {
  const auto ws = tiled(static_cast<int>(state.range(0)));
  WorkspaceEvaluator ev(ws);
  const auto& path = hand_path();
  HandState hand;
  hand.velocity_m_s = {0.05, -0.02};
  ev.reset_rt(hand);
  std::size_t k = 0;
  std::uint64_t switches = 0;
  std::uint32_t last = ev.current_patch();
  for (auto _ : state) {
    hand.position_m = path[k++ & (path.size() - 1)];
    benchmark::DoNotOptimize(ev.force_rt(hand, 1e-3));
    switches += ev.current_patch() != last;
    last = ev.current_patch();
  }
  state.counters["patches"] = static_cast<double>(ws.patches.size());
  state.counters["max_cell_entries"] = static_cast<double>(ev.grid().max_cell_entries());
  state.counters["patch_changes_per_1k_ticks"] =
      benchmark::Counter(1000.0 * static_cast<double>(switches) / static_cast<double>(state.iterations()));
}
BENCHMARK(BM_WorkspaceTick)->Arg(1)->Arg(10)->Arg(100)->Arg(1000);

// The lookup alone, the part that depends on the number of patches.
void BM_WorkspaceLookup(benchmark::State& state) {
  const auto ws = tiled(static_cast<int>(state.range(0)));
  WorkspaceEvaluator ev(ws);
  const auto& path = hand_path();
  std::size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(ev.patch_at(path[k++ & (path.size() - 1)]));
}
BENCHMARK(BM_WorkspaceLookup)->Arg(1)->Arg(10)->Arg(100)->Arg(1000);

}  // namespace
}  // namespace sandpaper::runtime
