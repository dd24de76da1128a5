// sandpaper_bench_loop: times the servo loop itself on the simulated joystick with the monotonic
// clock (SCHED_FIFO when permitted): period p50/p99/p99.9/max and overruns over a long run.
// Printed (and written as JSON with --json-out), never asserted: this machine is shared and noisy.
//   sandpaper_bench_loop --rate 10000 --duration 60 [--material corduroy] [--spin-margin-us 20]
//                        [--cpu N] [--guard-periods 0] [--json-out FILE]
#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"

namespace {

using namespace sandpaper;

std::int64_t monotonic_ns() noexcept {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return std::int64_t{now.tv_sec} * 1'000'000'000 + now.tv_nsec;
}

// The sim joystick with a timestamp on every read: the read is the first thing a tick does, so the
// spacing of the reads is the tick period (the loop's own report has p50/p99/max but not p99.9).
class TimedSim final : public runtime::Device {
 public:
  TimedSim(runtime::DeviceLimits limits, std::size_t ticks) : sim_(std::move(limits), {}, 0) { read_ns_.reserve(ticks); }
  const runtime::DeviceLimits& limits() const noexcept override { return sim_.limits(); }
  bool read_position_rt(double t_s, glm::dvec2& p) noexcept override {
    if (read_ns_.size() < read_ns_.capacity()) read_ns_.push_back(monotonic_ns());
    return sim_.read_position_rt(t_s, p);
  }
  bool write_force_rt(glm::dvec2 f) noexcept override { return sim_.write_force_rt(f); }
  const std::vector<std::int64_t>& reads() const noexcept { return read_ns_; }

 private:
  runtime::SimJoystick sim_;
  std::vector<std::int64_t> read_ns_;
};

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  const auto nth = v.begin() + static_cast<std::ptrdiff_t>(std::max<std::size_t>(rank, 1) - 1);
  std::nth_element(v.begin(), nth, v.end());
  return *nth;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Time the servo loop on the simulated joystick (monotonic clock)"};
  double rate = 1000, duration = 60;
  std::string material = "corduroy", json_out;
  app.add_option("--rate", rate, "servo rate, Hz")->capture_default_str();
  app.add_option("--duration", duration, "run length, s")->capture_default_str();
  app.add_option("--material", material, "material expression or library name to play")->capture_default_str();
  app.add_option("--json-out", json_out, "also write the figures as JSON to this file");
  runtime::ServoConfig defaults;
  double spin_margin_us = defaults.spin_margin_s * 1e6, guard_periods = defaults.deadline_guard_periods;
  int cpu = -1;
  app.add_option("--spin-margin-us", spin_margin_us, "sleep to this long before each deadline, then spin, us")->capture_default_str();
  app.add_option("--guard-periods", guard_periods, "deadline guard, periods (0: 50 ms)")->capture_default_str();
  app.add_option("--cpu", cpu, "pin the servo thread to this CPU (-1: not pinned)")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  compiler::CompileOptions options;
  options.library_dir = std::string(SANDPAPER_SOURCE_DIR) + "/library";
  options.calibration_dir = std::string(SANDPAPER_SOURCE_DIR) + "/calibration";
  const compiler::Compiler compiler(options);
  auto r = compiler.compile_text(material);
  if (!r.ok()) {
    std::cerr << compiler::format_diagnostics(r.diagnostics);
    return 1;
  }
  runtime::ServoConfig cfg;
  cfg.rate_hz = rate;
  cfg.duration_s = duration;
  cfg.spin_margin_s = spin_margin_us * 1e-6;
  cfg.deadline_guard_periods = guard_periods;
  cfg.cpu = cpu;
  const auto ticks = static_cast<std::size_t>(std::llround(rate * duration));
  TimedSim device(runtime::sim_device_limits(), ticks);
  runtime::PatchEvaluator evaluator(*r.program);
  const auto report = runtime::run_servo_thread_nonrt(device, evaluator, cfg);

  std::vector<double> period_us;
  const auto& reads = device.reads();
  for (std::size_t k = 1; k < reads.size(); ++k) period_us.push_back(1e-3 * static_cast<double>(reads[k] - reads[k - 1]));
  const double target_us = 1e6 / rate;
  std::size_t late = 0;  // periods longer than 1.5 x the target
  for (double p : period_us) late += p > 1.5 * target_us;
  const double p50 = percentile(period_us, 0.5), p99 = percentile(period_us, 0.99), p999 = percentile(period_us, 0.999);
  const double pmax = period_us.empty() ? 0 : *std::max_element(period_us.begin(), period_us.end());

  fmt::print("loop {} on sim at {:g} Hz for {:g} s: {} ticks, achieved {:.3f} Hz, {}\n", material, rate, duration,
             report.ticks, report.rate_hz, report.realtime_scheduling ? "SCHED_FIFO" : "normal priority (no SCHED_FIFO)");
  fmt::print("  period  target {:.1f} us; p50 {:.1f}, p99 {:.1f}, p99.9 {:.1f}, max {:.1f} us\n", target_us, p50, p99,
             p999, pmax);
  const double late_percent = report.ticks ? 100.0 * static_cast<double>(report.overruns) / static_cast<double>(report.ticks) : 0;
  fmt::print("  late ticks (started > half a period late) {} ({:.3f} %); periods > 1.5 x target {}; stalls (> 5 periods) {}, longest {:.1f} us\n",
             report.overruns, late_percent, late, report.stalls, report.longest_stall_us);
  fmt::print("  spin margin {:g} us, cpu {}, guard {:g} periods\n", spin_margin_us, report.cpu, guard_periods);
  fmt::print("  compute p50 {:.2f}, p99 {:.2f}, max {:.2f} us; stop: {}\n", report.compute_p50_us, report.compute_p99_us,
             report.compute_max_us, report.stop_reason);
  if (!json_out.empty()) {
    nlohmann::json j{{"material", material},       {"rate_hz_target", rate},
                     {"duration_s", duration},     {"ticks", report.ticks},
                     {"rate_hz", report.rate_hz},  {"sched_fifo", report.realtime_scheduling},
                     {"period_us", {{"p50", p50}, {"p99", p99}, {"p99_9", p999}, {"max", pmax}}},
                     {"overruns", report.overruns}, {"late_ticks_percent", late_percent}, {"periods_over_1_5x", late},
                     {"stalls", {{"count", report.stalls}, {"longest_us", report.longest_stall_us}}},
                     {"spin_margin_us", spin_margin_us}, {"cpu", report.cpu}, {"guard_periods", guard_periods},
                     {"compute_us", {{"p50", report.compute_p50_us}, {"p99", report.compute_p99_us}, {"max", report.compute_max_us}}},
                     {"stop_reason", report.stop_reason}};
    std::ofstream(json_out) << j.dump(2) << "\n";
  }
  return report.stop_reason == "completed" ? 0 : 1;
}
