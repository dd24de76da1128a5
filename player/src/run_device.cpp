#include "sandpaper/player/run_device.hpp"
#include "sandpaper/schema/input_limits.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include <fmt/format.h>

#include "sandpaper/player/exit_codes.hpp"
#include "sandpaper/runtime/trace_csv.hpp"

namespace sandpaper::cli {

void add_run_device_options(CLI::App* run, RunDeviceOptions& d) {
  run->add_option("--hand-model", d.hand_model,
                  "simulated hand: position (the handle follows the script) or dynamic (a mass pulled along it by "
                  "the hand's spring and damper, so forces move it)")
      ->check(CLI::IsMember({"position", "dynamic"}))
      ->capture_default_str();
  run->add_option("--hand-mass", d.hand.mass_kg, "dynamic hand: handle and hand mass, kg")
      ->check(CLI::PositiveNumber)->capture_default_str();
  run->add_option("--hand-stiffness", d.hand.stiffness_N_per_m, "dynamic hand: hand stiffness, N/m")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  run->add_option("--hand-damping", d.hand.damping_Ns_per_m, "dynamic hand: hand damping, N*s/m")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  run->add_option("--replay", d.replay,
                  "play the handle positions of a trace written by --trace, one per tick, instead of a scripted hand "
                  "(plays the whole trace; --duration and the hand options do not apply)");
  run->add_flag("--uncalibrated", d.uncalibrated,
                "with --device evdev[:PATH]: play a force-feedback input device that no calibration file names, with the "
                "uncalibrated-evdev profile (at most a quarter of its strongest force; newtons, travel and directions "
                "assumed; docs/DEVICES.md)");
}

int load_replay(const RunDeviceOptions& d, double rate_hz, std::vector<glm::dvec2>& positions, double& duration_s) {
  std::string text;
  try {
    text = schema::read_input_file(d.replay, schema::limits::kMaxTextFileBytes);
  } catch (const schema::InputFileError& e) {
    std::cerr << "sandpaper: error: cannot read the trace to replay '" << d.replay << "': " << e.reason << "\n";
    return kExitBadInput;
  }
  std::vector<runtime::TickRecord> trace;
  try {
    trace = runtime::parse_trace_csv(text);
  } catch (const std::invalid_argument& e) {
    std::cerr << d.replay << ": error: " << e.what() << "\n";
    return kExitBadInput;
  }
  if (trace.empty()) {
    std::cerr << d.replay << ": error: the trace has no ticks to replay\n";
    return kExitBadInput;
  }
  if (trace.size() >= 2) {
    // Each recorded position is played at one tick: the trace's own rate must be the one asked for.
    const double recorded_hz = static_cast<double>(trace.size() - 1) / (trace.back().t_s - trace.front().t_s);
    if (!(std::abs(recorded_hz - rate_hz) <= 0.01 * rate_hz)) {
      std::cerr << fmt::format("sandpaper: error: {} was recorded at {:.6g} Hz, not {:g} Hz; replay it with --rate {:.6g}\n",
                               d.replay, recorded_hz, rate_hz, recorded_hz);
      return kExitUsage;
    }
  }
  positions.clear();
  for (const auto& t : trace) positions.push_back(t.position_m);
  duration_s = static_cast<double>(trace.size()) / rate_hz;
  return kExitOk;
}

}  // namespace sandpaper::cli
