// A real-time run: 2 s of the servo loop at 1 kHz on the sim joystick with the monotonic clock.
// The counters are what matters (achieved rate and period spread), not the wall time.
#include <benchmark/benchmark.h>

#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"

namespace sandpaper::runtime {
namespace {

void BM_ServoLoopRealTime1kHz(benchmark::State& state) {
  schema::PatchProgram program;
  schema::GratingTerm grating;
  grating.period_m = 0.0025;
  grating.force_N = {0.0f, 1.0f, 2.0f, 1.0f, 0.0f, -1.0f, -2.0f, -1.0f};
  schema::DamperTerm damper;
  damper.damping_Ns_per_m = 1;
  program.terms = {grating, damper};
  PatchEvaluator evaluator(program);
  ServoConfig config;
  config.rate_hz = 1000;
  config.duration_s = 2.0;

  ServoReport report;
  for (auto _ : state) {
    SimJoystick joystick(sim_device_limits(), HandScript{}, 2000);
    report = run_servo_thread_nonrt(joystick, evaluator, config);
  }
  state.counters["ticks"] = static_cast<double>(report.ticks);
  state.counters["rate_hz"] = report.rate_hz;
  state.counters["period_p50_us"] = report.period_p50_us;
  state.counters["period_p99_us"] = report.period_p99_us;
  state.counters["period_max_us"] = report.period_max_us;
  state.counters["jitter_us"] = report.jitter_us;
  state.counters["compute_p99_us"] = report.compute_p99_us;
  state.counters["overruns"] = static_cast<double>(report.overruns);
  state.counters["sched_fifo"] = report.realtime_scheduling ? 1 : 0;
  if (report.stop_reason != "completed") state.SkipWithError(report.stop_reason.c_str());
}
BENCHMARK(BM_ServoLoopRealTime1kHz)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace sandpaper::runtime

BENCHMARK_MAIN();
