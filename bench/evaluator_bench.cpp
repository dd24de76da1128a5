// Cost of one PatchEvaluator::force_rt call: the servo tick's budget is ~1 ms at 1 kHz and
// 100 us at 10 kHz, shared with the device I/O.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "sandpaper/runtime/patch_evaluator.hpp"

namespace sandpaper::runtime {
namespace {

schema::GratingTerm bench_grating(std::size_t samples) {
  schema::GratingTerm grating;
  grating.period_m = 0.0025;
  grating.orientation_rad = 0.3;
  for (std::size_t i = 0; i < samples; ++i)
    grating.force_N.push_back(static_cast<float>(std::sin(6.283185307179586 * static_cast<double>(i) / static_cast<double>(samples))));
  return grating;
}

schema::HeightFieldTerm bench_height_field(std::uint32_t n) {
  schema::HeightFieldTerm field;
  field.nx = field.ny = n;
  field.origin_m[0] = field.origin_m[1] = -0.0475;
  field.spacing_m[0] = field.spacing_m[1] = 0.095 / n;
  field.repeat = true;
  for (std::uint32_t i = 0; i < n * n; ++i) {
    field.force_x_N.push_back(static_cast<float>(std::sin(0.37 * i)));
    field.force_y_N.push_back(static_cast<float>(std::cos(0.91 * i)));
  }
  return field;
}

// Walks the hand over the patch so every call lands somewhere new (no constant folding, and a
// realistic spread of table cells for the cache).
void play(benchmark::State& state, const schema::PatchProgram& program) {
  PatchEvaluator evaluator(program);
  HandState hand;
  hand.velocity_m_s = {0.05, -0.02};
  double t = 0;
  for (auto _ : state) {
    t += 1e-3;
    hand.position_m = {0.04 * std::sin(t * 1.3), 0.04 * std::cos(t * 0.7)};
    benchmark::DoNotOptimize(evaluator.force_rt(hand, 1e-3));
  }
}

void BM_ForceGrating1024(benchmark::State& state) {
  schema::PatchProgram program;
  program.terms.push_back(bench_grating(1024));
  play(state, program);
}
BENCHMARK(BM_ForceGrating1024);

void BM_ForceHeightField512(benchmark::State& state) {
  schema::PatchProgram program;
  program.terms.push_back(bench_height_field(512));
  play(state, program);
}
BENCHMARK(BM_ForceHeightField512);

void BM_ForceFourTerms(benchmark::State& state) {
  schema::PatchProgram program;
  schema::SpringTerm spring;
  spring.stiffness_N_per_m = 150;
  schema::DamperTerm damper;
  damper.damping_Ns_per_m = 2;
  program.terms = {spring, damper, bench_grating(1024), bench_height_field(512)};
  play(state, program);
}
BENCHMARK(BM_ForceFourTerms);

}  // namespace
}  // namespace sandpaper::runtime
