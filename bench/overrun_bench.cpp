// sandpaper_bench_overruns: how often the player's ticks start late, beside a bare clock_nanosleep
// loop at the same period on the same machine in the same minute. Rounds alternate three loops so
// each sees the same load: `bare` (sleep to each absolute deadline, read the clock, nothing else),
// `loop` (the servo loop on the simulated joystick, no telemetry) and `player` (what `sandpaper-play`
// runs while playing: cli::play, with its telemetry ring and the reader thread draining it). All
// three ask for the same thread settings (SCHED_FIFO 80, 1 ns timer slack, --cpu), and count a tick
// late as the servo loop does: started more than half a period after its deadline, deadlines
// k * period from the start. Printed (and written as JSON with --json-out), never asserted: the
// figures mean something only on a quiet machine (docs/RUNTIME.md, "Late ticks").
//   sandpaper_bench_overruns --rate 10000 --seconds 60 [--rounds 6] [--spin-margin-us 20] [--cpu N]
#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/player/play.hpp"
#include "sandpaper/runtime/devices/open_device.hpp"
#include "sandpaper/runtime/servo_loop.hpp"

namespace {

using namespace sandpaper;

constexpr std::int64_t kNsPerS = 1'000'000'000;

std::int64_t monotonic_ns() noexcept {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return std::int64_t{now.tv_sec} * kNsPerS + now.tv_nsec;
}

struct Tally {
  std::uint64_t ticks = 0, late = 0, stalls = 0;
  double longest_stall_us = 0;
  bool fifo = false;
  void add(const Tally& o) {
    ticks += o.ticks;
    late += o.late;
    stalls += o.stalls;
    longest_stall_us = std::max(longest_stall_us, o.longest_stall_us);
    fifo = o.fifo;
  }
  double late_fraction() const { return ticks ? static_cast<double>(late) / static_cast<double>(ticks) : 0; }
};

// The bare loop, on a thread set up as the servo thread is (servo_thread.cpp): no spin, no work.
Tally bare_loop(double rate_hz, double seconds, int cpu) {
  Tally t;
  std::thread thread([&] {
    sched_param param{};
    param.sched_priority = std::min(80, sched_get_priority_max(SCHED_FIFO));
    t.fifo = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0;
    prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
    if (cpu >= 0) {
      cpu_set_t one;
      CPU_ZERO(&one);
      CPU_SET(cpu, &one);
      pthread_setaffinity_np(pthread_self(), sizeof one, &one);
    }
    const double period_ns = kNsPerS / rate_hz;
    const auto ticks = static_cast<std::uint64_t>(std::llround(rate_hz * seconds));
    const std::int64_t start = monotonic_ns();
    std::int64_t previous = start;
    for (std::uint64_t k = 0; k < ticks; ++k) {
      const std::int64_t deadline = start + static_cast<std::int64_t>(std::llround(static_cast<double>(k) * period_ns));
      timespec wake{static_cast<time_t>(deadline / kNsPerS), static_cast<long>(deadline % kNsPerS)};
      while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr) == EINTR) {
      }
      const std::int64_t now = monotonic_ns();
      t.late += static_cast<double>(now - deadline) > 0.5 * period_ns;
      if (k > 0 && static_cast<double>(now - previous) > 5 * period_ns) {
        ++t.stalls;
        t.longest_stall_us = std::max(t.longest_stall_us, static_cast<double>(now - previous) * 1e-3);
      }
      previous = now;
      ++t.ticks;
    }
  });
  thread.join();
  return t;
}

Tally of(const runtime::ServoReport& r) {
  Tally t;
  t.ticks = r.ticks;
  t.late = r.overruns;
  t.stalls = r.stalls;
  t.longest_stall_us = r.longest_stall_us;
  t.fifo = r.realtime_scheduling;
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Late ticks of the player beside a bare clock_nanosleep loop (same period, same minute)"};
  double rate = 10000, seconds = 60, spin_margin_us = runtime::ServoConfig{}.spin_margin_s * 1e6;
  int rounds = 6, cpu = -1;
  std::string material = "roughness 0.6; grating period 2.5 mm", json_out;
  app.add_option("--rate", rate, "servo rate, Hz")->capture_default_str();
  app.add_option("--seconds", seconds, "time each loop runs in all, s (split over the rounds)")->capture_default_str();
  app.add_option("--rounds", rounds, "rounds of bare, loop, player in turn")->capture_default_str()->check(CLI::Range(1, 1000));
  app.add_option("--material", material, "material the loop and the player play")->capture_default_str();
  app.add_option("--spin-margin-us", spin_margin_us, "the servo loop's spin margin, us")->capture_default_str();
  app.add_option("--cpu", cpu, "pin every loop's thread to this CPU (-1: not pinned)")->capture_default_str();
  app.add_option("--json-out", json_out, "also write the figures as JSON to this file");
  CLI11_PARSE(app, argc, argv);

  compiler::CompileOptions options;
  options.library_dir = std::string(SANDPAPER_SOURCE_DIR) + "/library";
  options.calibration_dir = std::string(SANDPAPER_SOURCE_DIR) + "/calibration";
  const compiler::Compiler compiler(options);
  const auto r = compiler.compile_text(material);
  if (!r.ok()) {
    std::cerr << compiler::format_diagnostics(r.diagnostics);
    return 1;
  }
  const double each_s = seconds / rounds;
  runtime::ServoConfig cfg;
  cfg.rate_hz = rate;
  cfg.duration_s = each_s;
  cfg.spin_margin_s = spin_margin_us * 1e-6;
  cfg.cpu = cpu;

  const auto program = std::make_shared<const schema::PatchProgram>(*r.program);
  std::map<std::string, Tally> total;
  for (int round = 0; round < rounds; ++round) {
    total["bare"].add(bare_loop(rate, each_s, cpu));
    {
      auto opened = runtime::open_device(compiler.calibration(), runtime::DeviceSpec{});
      runtime::PatchEvaluator evaluator(*r.program);
      total["loop"].add(of(runtime::run_servo_thread_nonrt(*opened.device, evaluator, cfg)));
    }
    {
      auto opened = runtime::open_device(compiler.calibration(), runtime::DeviceSpec{});
      const auto played = cli::play(*opened.device, runtime::patch_source_for(*opened.device, program), cfg,
                                    /*virtual_clock=*/false, /*live=*/false, /*keep_records=*/0, &*r.program);
      total["player"].add(of(played.report));
    }
  }

  const double bare = total["bare"].late_fraction();
  fmt::print("late ticks at {:g} Hz, {} rounds of {:g} s each, spin margin {:g} us, cpu {} ({}):\n", rate, rounds,
             each_s, spin_margin_us, cpu, total["bare"].fifo ? "SCHED_FIFO" : "normal priority: SCHED_FIFO refused");
  nlohmann::json j{{"rate_hz", rate}, {"rounds", rounds}, {"seconds_each", each_s}, {"spin_margin_us", spin_margin_us},
                   {"cpu", cpu}, {"material", material}};
  for (const char* name : {"bare", "loop", "player"}) {
    const Tally& t = total[name];
    const double ratio = bare > 0 ? t.late_fraction() / bare : 0;
    fmt::print("  {:6}  {:>9} ticks  {:>8} late ({:6.3f} %, {:5.2f} x bare)  {:>6} stalls, longest {:.0f} us\n", name,
               t.ticks, t.late, 100 * t.late_fraction(), ratio, t.stalls, t.longest_stall_us);
    j[name] = {{"ticks", t.ticks}, {"late", t.late}, {"late_fraction", t.late_fraction()}, {"ratio_to_bare", ratio},
               {"stalls", t.stalls}, {"longest_stall_us", t.longest_stall_us}, {"sched_fifo", t.fifo}};
  }
  if (!json_out.empty()) std::ofstream(json_out) << j.dump(2) << "\n";
  return 0;
}
