// The 2-D servo tick of a real compiled material, whole: what one tick of the player costs on the
// servo thread, and what the telemetry reader then does with that tick's record. For comparing
// revisions (bench/compare_revisions.sh): it uses only runtime and compiler API that has not
// changed since 659b60d, so the same file builds against an older tree's headers.
//   BM_Evaluator/<m>            PatchEvaluator::force_rt for the whole compiled program (one call)
//   BM_Servo1000Ticks/<m>       run_servo_loop as the player runs it (LiveServo: the owning, swappable
//                               patch source, velocity filters, ramp, clamp, the sim joystick's read and
//                               write, the telemetry push) on the virtual clock: 1000 ticks at 1 kHz
//                               a run, so its time in us is ns per tick (also the ns_per_tick counter)
//   BM_Reader1000Records/<m>    the reader's share of those 1000 ticks: push + TelemetryReader::drain_nonrt
//                               with the felt-peak meter and TextureForce::at_nonrt at every record
//   BM_TextureForceSetup/<m>    TextureForce::for_program: once a run, not a tick (texture_force.cpp)
// Counters named fig_* are the figures played (forces in N), not timings: two revisions that keep
// the 2-D path's figures print the same ones (compare_revisions.sh checks them).
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "compiled_material.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/runtime/live_servo.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/runtime/telemetry.hpp"
#include "sandpaper/runtime/texture_force.hpp"

namespace sandpaper {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = SANDPAPER_SOURCE_DIR;
constexpr std::size_t kTicks = 1000;
constexpr double kRateHz = 1000;

std::shared_ptr<const schema::PatchProgram> program_for(const std::string& file) {
  return bench::compiled_material(file);
}

// The hand wandering over the patch, as material_bench.cpp and evaluator_bench.cpp walk it.
runtime::HandState wander(double t) {
  runtime::HandState hand;
  hand.velocity_m_s = {0.05, -0.02};
  hand.position_m = {0.04 * std::sin(t * 1.3), 0.04 * std::cos(t * 0.7)};
  return hand;
}

runtime::ServoConfig run_config() {
  runtime::ServoConfig config;
  config.rate_hz = kRateHz;
  config.duration_s = static_cast<double>(kTicks) / kRateHz;
  return config;
}

void BM_Evaluator(benchmark::State& state, std::string file) {
  const auto program = program_for(file);
  if (!program) {
    state.SkipWithError("did not compile");
    return;
  }
  {
    // The figure: sum of |F| over the first 1000 steps of the walk, from a fresh evaluator.
    runtime::PatchEvaluator fresh(*program);
    double sum = 0;
    for (std::size_t k = 1; k <= kTicks; ++k) {
      const auto f = fresh.force_rt(wander(1e-3 * static_cast<double>(k)), 1e-3);
      sum += std::hypot(f.x, f.y);
    }
    state.counters["fig_sum_F_N"] = sum;
  }
  runtime::PatchEvaluator evaluator(*program);
  double t = 0;
  for (auto _ : state) {
    t += 1e-3;
    benchmark::DoNotOptimize(evaluator.force_rt(wander(t), 1e-3));
  }
  state.counters["terms"] = static_cast<double>(program->terms.size());
}

void BM_Servo1000Ticks(benchmark::State& state, std::string file) {
  const auto program = program_for(file);
  if (!program) {
    state.SkipWithError("did not compile");
    return;
  }
  runtime::SimJoystick sim(runtime::sim_device_limits(), runtime::HandScript{}, 0);
  runtime::LiveServo::Options options;
  options.telemetry_records = kTicks + 1;
  runtime::LiveServo host(sim, runtime::patch_source_for(sim, program), options);
  runtime::TelemetryRing& ring = *host.telemetry();
  const runtime::ServoConfig config = run_config();
  runtime::ServoReport report;
  double sum_F = 0;
  for (auto _ : state) {
    report = host.run_virtual_nonrt(config);
    state.PauseTiming();
    runtime::TelemetryRecord r;
    sum_F = 0;
    while (ring.pop_nonrt(r)) sum_F += std::hypot(r.force_N.x, r.force_N.y);
    state.ResumeTiming();
  }
  if (report.stop_cause != runtime::StopCause::Completed || report.ticks != kTicks || ring.dropped() != 0) {
    state.SkipWithError(("the run did not play every tick: " + report.stop_reason).c_str());
    return;
  }
  // Seconds of CPU time per tick (printed as e.g. 95.2n).
  state.counters["ns_per_tick"] = benchmark::Counter(static_cast<double>(kTicks),
                                                     benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
  state.counters["fig_sum_F_N"] = sum_F;
  state.counters["fig_felt_max_N"] = report.felt_max_lateral_force_N;
  state.counters["fig_clamped_ticks"] = static_cast<double>(report.clamped_ticks);
}

void BM_Reader1000Records(benchmark::State& state, std::string file) {
  const auto program = program_for(file);
  if (!program) {
    state.SkipWithError("did not compile");
    return;
  }
  // The records of one run, as the servo thread pushed them.
  std::vector<runtime::TelemetryRecord> records;
  {
    runtime::SimJoystick sim(runtime::sim_device_limits(), runtime::HandScript{}, 0);
    runtime::LiveServo::Options options;
    options.telemetry_records = kTicks + 1;
    runtime::LiveServo host(sim, runtime::patch_source_for(sim, program), options);
    host.run_virtual_nonrt(run_config());
    runtime::TelemetryRecord r;
    while (host.telemetry()->pop_nonrt(r)) records.push_back(r);
  }
  runtime::TelemetryRing ring(kTicks + 1);
  std::unique_ptr<runtime::TelemetryReader> reader;
  for (auto _ : state) {
    state.PauseTiming();
    reader = std::make_unique<runtime::TelemetryReader>(ring, kRateHz, 0);
    reader->measure_felt_peak(*program, run_config().ramp_s);
    state.ResumeTiming();
    for (const auto& r : records) ring.push_rt(r);
    benchmark::DoNotOptimize(reader->drain_nonrt());
  }
  const auto* felt = reader->felt();
  state.counters["fig_felt_peak_N"] = felt && felt->felt_peak_N() ? *felt->felt_peak_N() : -1.0;
  state.counters["fig_texture_max_N"] = reader->felt_texture_max_N().value_or(-1.0);
  state.counters["fig_mean_F_N"] = reader->mean_force_N();
}

void BM_TextureForceSetup(benchmark::State& state, std::string file) {
  const auto program = program_for(file);
  if (!program) {
    state.SkipWithError("did not compile");
    return;
  }
  for (auto _ : state) {
    auto texture = runtime::TextureForce::for_program(*program);
    benchmark::DoNotOptimize(texture);
  }
}

// The corduroy a designer writes (a grating) and a photograph's height field.
const char* const kMaterials[][2] = {
    {"corduroy", "examples/corduroy.hmat"},
    {"sandpaper-p80", "library/abrasives/sandpaper-p80.hmat"},
};

const int registered = [] {
  for (const auto& [name, file] : kMaterials) {
    const std::string n = name;
    benchmark::RegisterBenchmark(("BM_Evaluator/" + n).c_str(), BM_Evaluator, std::string(file));
    benchmark::RegisterBenchmark(("BM_Servo1000Ticks/" + n).c_str(), BM_Servo1000Ticks, std::string(file))
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("BM_Reader1000Records/" + n).c_str(), BM_Reader1000Records, std::string(file))
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("BM_TextureForceSetup/" + n).c_str(), BM_TextureForceSetup, std::string(file))
        ->Unit(benchmark::kMicrosecond);
  }
  return 0;
}();

}  // namespace
}  // namespace sandpaper

BENCHMARK_MAIN();
