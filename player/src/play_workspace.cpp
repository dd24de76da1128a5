#include "sandpaper/player/play_workspace.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "sandpaper/player/exit_codes.hpp"
#include "sandpaper/player/play.hpp"
#include "sandpaper/runtime/devices/open_device.hpp"
#include "sandpaper/runtime/workspace_evaluator.hpp"
#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/json_text.hpp"

namespace sandpaper::cli {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The default hand: a scan through the workspace centre along the direction (of 16) that crosses
// the most patches, turning just beyond the furthest patch it meets (within the device's reach).
struct ScanChoice {
  double direction_rad = 0;
  double amplitude_m = 0.03;
  std::size_t crossed = 0;
};

ScanChoice choose_scan(const runtime::WorkspaceEvaluator& ev, double reach_m) {
  ScanChoice best;
  constexpr int kDirections = 16;
  constexpr double kStep_m = 0.25e-3;
  const int steps = static_cast<int>(reach_m / kStep_m);
  for (int k = 0; k < kDirections; ++k) {
    const double a = kPi * k / kDirections;
    const glm::dvec2 dir{std::cos(a), std::sin(a)};
    std::vector<bool> hit(ev.patch_count(), false);
    std::size_t crossed = 0;
    double furthest = 0;
    for (int s = -steps; s <= steps; ++s) {
      const double d = s * kStep_m;
      const auto id = ev.patch_at(d * dir);
      if (id == runtime::WorkspaceEvaluator::kNoPatch) continue;
      furthest = std::max(furthest, std::abs(d));
      if (!hit[id]) {
        hit[id] = true;
        ++crossed;
      }
    }
    if (crossed > best.crossed) best = {a, std::min(reach_m, furthest + 1e-3), crossed};
  }
  return best;
}

}  // namespace

std::string patch_line(const schema::WorkspaceProgram& ws, std::size_t i) {
  const auto& p = ws.patches[i];
  return fmt::format("patch {:<3} {:<24} at {:g} mm, {:g} mm  size {:g} x {:g} mm", i + 1, "\"" + p.source + "\"",
                     p.centre_m[0] * 1e3, p.centre_m[1] * 1e3, p.size_m[0] * 1e3, p.size_m[1] * 1e3);
}


WorkspaceRunOptions workspace_options_of(const PlayRequest& r, const CLI::App& run, double crossfade_ms) {
  WorkspaceRunOptions ro;
  ro.rate_hz = r.rate_hz;
  if (run.count("--duration")) ro.duration_s = r.duration_s;
  if (run.count("--hand")) ro.hand = r.hand;
  ro.speed_mm_s = r.speed_mm_s;
  if (run.count("--amplitude")) ro.amplitude_mm = r.amplitude_mm;
  ro.hand_start_mm = r.hand_start_mm;
  ro.trace = r.trace;
  ro.virtual_clock = r.virtual_clock;
  ro.crossfade_ms = crossfade_ms;
  ro.live = r.live;
  ro.json = r.json;
  ro.servo = servo_config_of(r);
  return ro;
}

int check_workspace_request(const WorkspaceRunOptions& ro, const runtime::DeviceLimits& limits) {
  if (!(ro.speed_mm_s > 0) || !std::isfinite(ro.speed_mm_s) ||
      (ro.amplitude_mm && (!(*ro.amplitude_mm > 0) || !std::isfinite(*ro.amplitude_mm)))) {
    std::cerr << "sandpaper: error: --speed and --amplitude must be positive (mm/s, mm)\n";
    return kExitUsage;
  }
  if (!std::isfinite(ro.hand_start_mm)) {
    std::cerr << "sandpaper: error: --hand-start must be a finite length, mm\n";
    return kExitUsage;
  }
  if (ro.amplitude_mm && *ro.amplitude_mm * 1e-3 > limits.workspace_radius_m) {
    std::cerr << "sandpaper: error: --amplitude " << *ro.amplitude_mm << " mm leaves the " << limits.workspace_radius_m * 1e3
              << " mm workspace radius of device '" << limits.name << "'\n";
    return kExitUsage;
  }
  if (!std::isfinite(ro.crossfade_ms) || ro.crossfade_ms < 0) {
    std::cerr << "sandpaper: error: --crossfade must be a time >= 0 ms\n";
    return kExitUsage;
  }
  return check_trace_folder(ro.trace);
}

int play_workspace_on_sim(const schema::WorkspaceProgram& ws, const calibration::CalibrationSet& set,
                          const WorkspaceRunOptions& ro) {
  // This one finds the patch under a position (the scan's aim, each tick's patch afterwards); the
  // run plays a copy of its own.
  runtime::WorkspaceEvaluator evaluator(ws, ro.crossfade_ms * 1e-3);
  const calibration::DeviceCalibration* sim = set.find_device("sim");
  if (sim == nullptr) {
    std::cerr << "sandpaper: error: the calibration has no device 'sim' to play workspaces on\n";
    return kExitUsage;
  }
  const runtime::DeviceLimits limits = runtime::limits_of(*sim);

  const std::string hand = ro.hand.value_or("scan");
  runtime::HandScript script;
  script.path = hand == "circle" ? runtime::HandPath::Circle : runtime::HandPath::Scan;
  script.speed_m_s = ro.speed_mm_s * 1e-3;
  const ScanChoice scan = choose_scan(evaluator, limits.workspace_radius_m);
  // An explicit --hand keeps the single-patch behaviour (scan along x); the default aims at the patches.
  script.direction_rad = ro.hand ? 0.0 : scan.direction_rad;
  script.amplitude_m = ro.amplitude_mm ? *ro.amplitude_mm * 1e-3 : scan.amplitude_m;
  script.start_m = ro.hand_start_mm * 1e-3;
  // By default one whole lap of the path: out to one end, across to the other and back to the centre.
  const double lap_m = hand == "circle" ? 2 * kPi * script.amplitude_m : 4 * script.amplitude_m;
  const double duration_s = ro.duration_s.value_or(lap_m / script.speed_m_s);

  // The simulated joystick below keeps a record of every tick.
  if (const int rc = check_run_length(duration_s, ro.rate_hz, true); rc != kExitOk) return rc;
  runtime::ServoConfig cfg = ro.servo;
  cfg.rate_hz = ro.rate_hz;
  cfg.duration_s = duration_s;
  try {
    runtime::validate_config(cfg, limits);
  } catch (const std::invalid_argument& e) {
    std::cerr << "sandpaper: error: " << e.what() << "\n";
    return kExitUsage;
  }
  const auto ticks = static_cast<std::size_t>(std::llround(duration_s * ro.rate_hz));
  // Through the device factory, as every run: the simulated joystick keeping a record of every tick.
  runtime::DeviceSpec spec;
  spec.device = "sim";
  spec.script = script;
  spec.record_ticks = ticks;
  spec.virtual_clock = ro.virtual_clock;
  runtime::OpenedDevice opened = runtime::open_device(set, std::move(spec));
  runtime::RecordingDevice& joystick = *opened.recording;
  if (!ro.json)
    std::cout << fmt::format("playing workspace \"{}\" ({} patches) on {}: {:g} Hz for {:g} s, hand {}{} at {:g} mm/s, {} {:g} mm{}\n",
                             ws.name, ws.patches.size(), limits.name, ro.rate_hz, duration_s, hand,
                             script.path == runtime::HandPath::Scan ? fmt::format(" along {:g} deg", script.direction_rad * 180 / kPi) : "",
                             ro.speed_mm_s, script.path == runtime::HandPath::Circle ? "radius" : "turning at +-",
                             script.amplitude_m * 1e3, ro.virtual_clock ? " (virtual clock)" : "");
  const Played played = play(joystick, std::make_unique<runtime::WorkspaceEvaluator>(ws, ro.crossfade_ms * 1e-3), cfg,
                             ro.virtual_clock, ro.live, ro.trace.empty() ? 0 : ticks, nullptr);
  const runtime::ServoReport& rep = played.report;

  // Which patch each tick was over, found again from the recorded positions (off the servo thread).
  const auto& recs = joystick.records();
  std::vector<std::uint64_t> ticks_on(ws.patches.size(), 0);
  std::vector<double> max_force(ws.patches.size(), 0.0);
  for (const auto& r : recs) {
    const auto id = evaluator.patch_at(r.position_m);
    if (id == runtime::WorkspaceEvaluator::kNoPatch) continue;
    ++ticks_on[id];
    max_force[id] = std::max(max_force[id], std::hypot(r.force_N.x, r.force_N.y));
  }
  std::size_t touched = 0;
  for (auto t : ticks_on) touched += t > 0;

  if (!ro.trace.empty()) {
    std::ostringstream csv;
    csv.precision(9);
    csv << "t_s,x_m,y_m,force_x_N,force_y_N,patch\n";
    for (const auto& r : played.records) {  // from the telemetry ring
      const auto id = evaluator.patch_at(r.position_m);
      csv << r.t_s << "," << r.position_m.x << "," << r.position_m.y << "," << r.force_N.x << "," << r.force_N.y << ","
          << (id == runtime::WorkspaceEvaluator::kNoPatch ? 0 : id + 1) << "\n";
    }
    schema::write_file_atomically(ro.trace, csv.str());
  }

  if (ro.json) {
    nlohmann::json patches = nlohmann::json::array();
    for (std::size_t i = 0; i < ws.patches.size(); ++i)
      patches.push_back({{"patch", i + 1},
                         {"source", ws.patches[i].source},
                         {"material", ws.patches[i].program->name},
                         {"touched", ticks_on[i] > 0},
                         {"ticks", ticks_on[i]},
                         {"felt_max_lateral_force_N", max_force[i]},
                         {"compiled_max_lateral_force_N", ws.patches[i].program->max_lateral_force_N}});
    nlohmann::json j{{"workspace", ws.name},
                     {"device", limits.name},
                     {"ticks", rep.ticks},
                     {"rate_hz", rep.rate_hz},
                     {"rate_hz_target", ro.rate_hz},
                     {"duration_s", duration_s},
                     {"period_us", {{"p50", rep.period_p50_us}, {"p99", rep.period_p99_us}, {"max", rep.period_max_us}, {"min", rep.period_min_us}}},
                     {"jitter_us", rep.jitter_us},
                     {"compute_us", {{"p50", rep.compute_p50_us}, {"p99", rep.compute_p99_us}, {"max", rep.compute_max_us}}},
                     {"overruns", rep.overruns},
                     {"stalls", {{"count", rep.stalls}, {"longest_us", rep.longest_stall_us}, {"threshold_periods", runtime::kStallPeriods}}},
                     {"felt_max_lateral_force_N", rep.felt_max_lateral_force_N},
                     {"clamped_ticks", rep.clamped_ticks},
                     {"stop_reason", rep.stop_reason},
                     {"stop_cause", runtime::stop_cause_name(rep.stop_cause)},
                     {"realtime_scheduling", rep.realtime_scheduling},
                     {"clock", ro.virtual_clock ? "virtual" : "monotonic"},
                     {"player", player_name()},
                     {"crossfade_ms", ro.crossfade_ms},
                     {"hand", {{"path", hand}, {"direction_deg", script.direction_rad * 180 / kPi}, {"speed_mm_s", ro.speed_mm_s},
                               {"amplitude_mm", script.amplitude_m * 1e3}}},
                     {"patch_count", ws.patches.size()},
                     {"touched_patches", touched},
                     {"patches", patches},
                     {"trace", ro.trace.empty() ? nlohmann::json(nullptr) : nlohmann::json(ro.trace)}};
    std::cout << schema::json_text(j, 2) << "\n";
  } else {
    std::cout << fmt::format("  loop     {} ticks, achieved {:.2f} Hz; period p50 {:.1f} us, p99 {:.1f} us, max {:.1f} us; "
                             "jitter {:.2f} us (sd); overruns {}; stalls {} (longest {:.0f} us)\n",
                             rep.ticks, rep.rate_hz, rep.period_p50_us, rep.period_p99_us, rep.period_max_us, rep.jitter_us,
                             rep.overruns, rep.stalls, rep.longest_stall_us);
    std::cout << fmt::format("  compute  p50 {:.2f} us, p99 {:.2f} us, max {:.2f} us per tick\n", rep.compute_p50_us,
                             rep.compute_p99_us, rep.compute_max_us);
    std::cout << fmt::format("  felt     max lateral force {:.4f} N, clamped ticks {}; crossfade {:g} ms at patch edges\n",
                             rep.felt_max_lateral_force_N, rep.clamped_ticks, ro.crossfade_ms);
    std::cout << fmt::format("  patches  {} of {} touched (patch 1 at the back)\n", touched, ws.patches.size());
    // A big workspace lists only the patches the hand touched.
    const bool list_all = ws.patches.size() <= 24;
    for (std::size_t i = 0; i < ws.patches.size(); ++i) {
      if (ticks_on[i] == 0) {
        if (list_all) std::cout << "    " << patch_line(ws, i) << "  not touched\n";
        continue;
      }
      std::cout << "    " << patch_line(ws, i)
                << fmt::format("  {} ticks, max |F| {:.4f} N (compiled {:.4f} N)\n", ticks_on[i], max_force[i],
                               ws.patches[i].program->max_lateral_force_N);
    }
    if (!list_all && touched < ws.patches.size())
      std::cout << "    (" << ws.patches.size() - touched << " patches not touched)\n";
    std::cout << "  servo    " << (ro.virtual_clock ? "virtual clock" : rep.realtime_scheduling ? "SCHED_FIFO, memory locked"
                                                                   : "normal priority (SCHED_FIFO not permitted here)")
              << "; stopped: " << rep.stop_reason << "\n";
    if (!ro.trace.empty()) std::cout << "  trace    " << ro.trace << " (" << recs.size() << " ticks)\n";
  }
  return exit_status_of(rep);
}

}  // namespace sandpaper::cli
