// Cost of one PatchEvaluator::force_rt call: the servo tick's budget is ~1 ms at 1 kHz and
// 100 us at 10 kHz, shared with the device I/O. BM_Term/<kind> plays a program of that one term kind
// (tick cost per force term, state advance and energy metering included).
#include <benchmark/benchmark.h>

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <memory>
#include <utility>
#include <variant>
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

// One term of one kind, played with an energy budget that never runs dry so the tank's metering is
// timed but never scales.
void BM_Term(benchmark::State& state, schema::Term term) {
  if (const auto* masses = std::get_if<schema::PointMassesTerm>(&term))
    state.counters["substeps"] = std::min(PatchEvaluator::substeps_for(*masses, 1e-3), kMaxPointMassSubsteps);
  schema::PatchProgram program;
  program.terms.push_back(std::move(term));
  program.energy_budget_J = 1e12;
  play(state, program);
}

schema::PointMassesTerm bench_masses(std::uint32_t count, double k0) {
  schema::PointMassesTerm m;
  m.count = count;
  m.mass_kg[0] = 0.05;
  m.mass_kg[1] = 0.03;
  m.stiffness_N_per_m[0] = k0;
  m.stiffness_N_per_m[1] = 150;
  m.damping_Ns_per_m[0] = 0.5;
  m.damping_Ns_per_m[1] = 0.3;
  m.ground_damping_Ns_per_m = 0.1;
  m.gravity_m_s2[1] = -9.81;
  return m;
}

schema::SpringTerm bench_spring() {
  schema::SpringTerm t;
  t.stiffness_N_per_m = 150;
  return t;
}
schema::DamperTerm bench_damper() {
  schema::DamperTerm t;
  t.damping_Ns_per_m = 2;
  return t;
}
schema::ConstantForceTerm bench_constant() {
  schema::ConstantForceTerm t;
  t.force_N[0] = 0.3;
  return t;
}
schema::NapTerm bench_nap() {
  schema::NapTerm t;
  t.damping_Ns_per_m = 2;
  return t;
}
schema::PeriodicTerm bench_periodic(schema::PeriodicShape shape) {
  schema::PeriodicTerm t;
  t.shape = shape;
  t.amplitude_N = 0.8;
  t.period_m = 0.004;
  return t;
}
schema::RidgeTerm bench_ridge() {
  schema::RidgeTerm t;
  t.stiffness_N_per_m = 300;
  t.wavelength_m = 0.006;
  t.ridge_width_m = 0.002;
  return t;
}
schema::BowlTerm bench_bowl() {
  schema::BowlTerm t;
  t.stiffness_N_per_m = 150;
  t.radius_m = 0.03;
  return t;
}
schema::LinearFieldTerm bench_linear_field() {
  schema::LinearFieldTerm t;
  t.radial_N_per_m = -50;
  t.tangential_N_per_m = 40;
  return t;
}
schema::LinearSpringTerm bench_linear_spring() {
  schema::LinearSpringTerm t;
  t.stiffness_N_per_m = 200;
  t.orientation_rad = 0.7;
  return t;
}
schema::MinusTerm bench_minus() {
  schema::MinusTerm t;
  t.stiffness_N_per_m = 100;
  t.lead_s = 0.02;
  return t;
}
schema::FollowerSpringTerm bench_follower() {
  schema::FollowerSpringTerm t;
  t.stiffness_N_per_m = 150;
  t.lag_s = 0.05;
  return t;
}
schema::AttractorTerm bench_attractor() {
  schema::AttractorTerm t;
  t.stiffness_N_per_m = 80;
  t.radius_m = 0.02;
  t.period_s = 1.5;
  t.swirl = 0.3;
  return t;
}

BENCHMARK_CAPTURE(BM_Term, spring, bench_spring());
BENCHMARK_CAPTURE(BM_Term, damper, bench_damper());
BENCHMARK_CAPTURE(BM_Term, grating_1024, bench_grating(1024));
BENCHMARK_CAPTURE(BM_Term, height_field_512, bench_height_field(512));
BENCHMARK_CAPTURE(BM_Term, constant_force, bench_constant());
BENCHMARK_CAPTURE(BM_Term, nap, bench_nap());
BENCHMARK_CAPTURE(BM_Term, periodic_sine, bench_periodic(schema::PeriodicShape::Sine));
BENCHMARK_CAPTURE(BM_Term, periodic_sawtooth, bench_periodic(schema::PeriodicShape::Sawtooth));
BENCHMARK_CAPTURE(BM_Term, periodic_triangle, bench_periodic(schema::PeriodicShape::Triangle));
BENCHMARK_CAPTURE(BM_Term, ridge, bench_ridge());
BENCHMARK_CAPTURE(BM_Term, bowl, bench_bowl());
BENCHMARK_CAPTURE(BM_Term, linear_field, bench_linear_field());
BENCHMARK_CAPTURE(BM_Term, linear_spring, bench_linear_spring());
BENCHMARK_CAPTURE(BM_Term, minus, bench_minus());
BENCHMARK_CAPTURE(BM_Term, follower_spring, bench_follower());
BENCHMARK_CAPTURE(BM_Term, point_masses_1, bench_masses(1, 200));
BENCHMARK_CAPTURE(BM_Term, point_masses_2, bench_masses(2, 200));
// Stiff enough (omega = 20000 rad/s) to need the 64-substep cap at the 1 ms tick: the most a
// point-masses term can cost per tick.
BENCHMARK_CAPTURE(BM_Term, point_masses_2_at_cap, bench_masses(2, 2e7));
BENCHMARK_CAPTURE(BM_Term, attractor, bench_attractor());

// Tick cost against texture size: a height field of n x n samples (two float grids, gradient x and
// y: 4096^2 is 128 MB), built once per size and kept, so the timing is of the lookup alone. The hand
// wanders over the whole patch, so larger grids miss the cache more.
const schema::PatchProgram& height_field_program(std::uint32_t n) {
  static std::vector<std::pair<std::uint32_t, std::unique_ptr<schema::PatchProgram>>> built;
  for (const auto& [size, program] : built)
    if (size == n) return *program;
  auto program = std::make_unique<schema::PatchProgram>();
  program->terms.push_back(bench_height_field(n));
  built.emplace_back(n, std::move(program));
  return *built.back().second;
}

void BM_HeightFieldSize(benchmark::State& state) {
  const auto n = static_cast<std::uint32_t>(state.range(0));
  const auto& program = height_field_program(n);
  state.counters["grid_MB"] = 2.0 * n * n * sizeof(float) / 1e6;
  play(state, program);
}
BENCHMARK(BM_HeightFieldSize)->Arg(64)->Arg(256)->Arg(1024)->Arg(4096);

void BM_GratingSize(benchmark::State& state) {
  schema::PatchProgram program;
  program.terms.push_back(bench_grating(static_cast<std::size_t>(state.range(0))));
  play(state, program);
}
BENCHMARK(BM_GratingSize)->Arg(64)->Arg(1024)->Arg(16384);


}  // namespace
}  // namespace sandpaper::runtime
