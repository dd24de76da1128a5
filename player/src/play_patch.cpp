#include "sandpaper/player/play_patch.hpp"

#include <CLI/CLI.hpp>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "sandpaper/player/exit_codes.hpp"
#include "sandpaper/player/play.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/trace_csv.hpp"
#include "sandpaper/runtime/usb/hid_pid_joystick.hpp"
#include "sandpaper/runtime/devices/open_device.hpp"
#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/schema/json_text.hpp"
#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::cli {
namespace {

// A row of block characters: the largest |F| in each slice of the first `span_ticks` ticks, so
// the texture's force pattern is visible (over a whole run every slice would reach the maximum).
std::string force_strip(const std::vector<runtime::TickRecord>& recs, double max_force, std::size_t width,
                        std::size_t span_ticks) {
  static const char* bars[] = {" ", "▁", "▂", "▃", "▄", "▅", "▆", "▇", "█"};
  if (recs.empty() || !(max_force > 0)) return {};
  std::string out;
  std::size_t span = std::min(span_ticks, recs.size());
  std::size_t per = std::max<std::size_t>(1, span / width);
  for (std::size_t i = 0; i + per <= span; i += per) {
    double m = 0;
    for (std::size_t k = i; k < i + per; ++k) m = std::max(m, std::hypot(recs[k].force_N.x, recs[k].force_N.y));
    out += bars[static_cast<int>(std::lround(8 * m / max_force))];
  }
  return out;
}

// Seconds of ticks the simulated device records: the force strip shows the first 256 ms, and the
// rest of the report comes from the telemetry, so a long run does not grow the process.
constexpr double kRecordedSeconds = 1.0;

nlohmann::json optional_json(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }

// The roughness the map predicts from what the hand felt of the texture: from the felt peak where
// the run crossed grating ridges (explain predicts the same quantity), else from the texture terms'
// largest |F| at the played positions; never from friction, springs or dampers beside the texture.
struct FeltRoughness {
  double roughness = 0;
  const char* from = "";
};
FeltRoughness felt_roughness_of(const Played& played, const runtime::ServoReport& rep,
                                const calibration::PsychophysicalMap& map) {
  if (played.felt_peak_N) return {map.percept_of(*played.felt_peak_N), "felt_peak_N"};
  if (played.felt_texture_max_N) return {map.percept_of(*played.felt_texture_max_N), "felt_texture_max_N"};
  return {map.percept_of(rep.felt_max_lateral_force_N), "felt_max_lateral_force_N"};
}

nlohmann::json stalls_json(const runtime::ServoReport& rep) {
  return {{"count", rep.stalls}, {"longest_us", rep.longest_stall_us}, {"threshold_periods", runtime::kStallPeriods}};
}

std::string stalls_text(const runtime::ServoReport& rep) {
  if (rep.stalls == 0) return fmt::format("no stalls (gaps over {:g} periods)", runtime::kStallPeriods);
  return fmt::format("{} stall{} (gaps over {:g} periods), longest {:.0f} us", rep.stalls, rep.stalls == 1 ? "" : "s",
                     runtime::kStallPeriods, rep.longest_stall_us);
}

// The caller's program, for a source that outlives nothing it plays in: play() ends before the
// program does, so no ownership is shared (an aliasing pointer with no owner).
std::shared_ptr<const schema::PatchProgram> borrowed(const schema::PatchProgram& program) {
  return {std::shared_ptr<const void>(), &program};
}

std::string describe_emulation(const PlayRequest& r) {
  const auto& q = r.quantization;
  return fmt::format("positions in {:.4g} mm steps, forces in {:.4g} mN steps up to {} units per axis, tables {}",
                     q.position_step_m * 1e3, q.force_step_N[0] * 1e3, q.command_max,
                     r.tables == runtime::TableSampling::Hold ? "sample-and-hold (Appendix B 2.1)" : "interpolated");
}

}  // namespace

std::string player_name() {
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("unknown") : self.filename().string();
}

void add_play_options(CLI::App* run, PlayRequest& r) {
  run->add_option("--rate", r.rate_hz, "servo rate, Hz (900 to 10000; an emulated device: its own rate)")
      ->each([&r](const std::string&) { r.rate_given = true; })
      ->capture_default_str();
  run->add_option("--duration", r.duration_s, "how long to play, s")->capture_default_str();
  run->add_option("--hand", r.hand, "simulated hand path")->check(CLI::IsMember({"scan", "circle"}))->capture_default_str();
  run->add_option("--speed", r.speed_mm_s, "hand speed, mm/s")->capture_default_str();
  run->add_option("--amplitude", r.amplitude_mm, "scan half-width or circle radius, mm")->capture_default_str();
  run->add_option("--hand-start", r.hand_start_mm,
                  "how far along its path the simulated hand starts, mm (0: the patch centre, heading +x); a "
                  "fraction of one tick's travel moves where every tick lands on a texture")
      ->capture_default_str();
  run->add_option("--trace", r.trace, "write every tick's time, position and force to this CSV file");
  run->add_flag("--virtual-clock", r.virtual_clock, "run on simulated time, as fast as possible (deterministic)");
  run->add_flag("--live", r.live, "print live servo figures on stderr once a second (default when stderr is a terminal)");
  run->add_option("--spin-margin", r.spin_margin_us,
                  "wake this long before each tick's deadline and spin to it, us (0: sleep only; docs/performance.md)")
      ->capture_default_str();
  add_guard_options(run, r.guards);
  run->add_option("--cpu", r.cpu, "pin the servo thread to this CPU (docs/RUNTIME.md: an isolated core)");
  add_run_device_options(run, r.device);
}

void apply_emulation(const calibration::DeviceCalibration& device, PlayRequest& r) {
  const auto emulation = runtime::emulation_of(device);
  if (!emulation) return;
  r.emulated = true;
  r.quantization = emulation->quantization;
  r.tables = emulation->tables;
  if (!r.rate_given) r.rate_hz = std::clamp(1000.0, device.min_rate_hz, device.max_rate_hz);
}

runtime::ServoConfig servo_config_of(const PlayRequest& r) {
  // An emulated device's command steps are its own (Device::command_quantum): the loop asks it.
  runtime::ServoConfig cfg;
  cfg.rate_hz = r.rate_hz;
  cfg.duration_s = r.duration_s;
  cfg.spin_margin_s = r.spin_margin_us * 1e-6;
  r.guards.apply(cfg);
  cfg.cpu = r.cpu;
  return cfg;
}

int check_trace_folder(const std::string& trace) {
  if (trace.empty()) return kExitOk;
  // Refuse an unwritable trace before playing, not after.
  auto dir = std::filesystem::path(trace).parent_path();
  if (dir.empty()) dir = ".";
  if (!std::filesystem::is_directory(dir) || access(dir.c_str(), W_OK) != 0) {
    std::cerr << "sandpaper: error: cannot write the trace '" << trace << "': folder " << dir
              << " does not exist or is not writable\n";
    return kExitUsage;
  }
  return kExitOk;
}

int check_run_length(double duration_s, double rate_hz, bool records_every_tick) {
  using schema::limits::kMaxRecordedTicks;
  using schema::limits::kMaxRunSeconds;
  if (!(duration_s >= 0 && duration_s <= kMaxRunSeconds)) {
    std::cerr << "sandpaper: error: --duration must be from 0 (until stopped) to " << kMaxRunSeconds << " s\n";
    return kExitUsage;
  }
  if (records_every_tick && std::isfinite(rate_hz) && duration_s * rate_hz > static_cast<double>(kMaxRecordedTicks)) {
    std::cerr << fmt::format(
        "sandpaper: error: a run that records every tick (--virtual-clock, --trace, the simulated joystick) is at most "
        "{} ticks: {:g} s at {:g} Hz; give a shorter --duration (docs/RELIABILITY.md)\n",
        kMaxRecordedTicks, static_cast<double>(kMaxRecordedTicks) / rate_hz, rate_hz);
    return kExitUsage;
  }
  return kExitOk;
}

int check_play_request(const PlayRequest& r, const runtime::DeviceLimits& limits) {
  // The virtual clock's telemetry ring and a --trace hold every tick until the run ends.
  const bool records = r.virtual_clock || !r.trace.empty();
  if (const int rc = check_run_length(r.duration_s, r.rate_hz, records); rc != kExitOk) return rc;
  runtime::ServoConfig cfg = servo_config_of(r);
  std::atomic<bool> stop{false};
  cfg.stop_request = &stop;  // play() always has one: a run until stopped is allowed
  try {
    runtime::validate_config(cfg, limits);
  } catch (const std::invalid_argument& e) {
    std::cerr << "sandpaper: error: " << e.what() << "\n";
    return kExitUsage;
  }
  if (r.virtual_clock && r.duration_s == 0) {
    std::cerr << "sandpaper: error: --virtual-clock needs a --duration (a simulated run cannot be stopped by hand)\n";
    return kExitUsage;
  }
  if (!std::isfinite(r.hand_start_mm)) {
    std::cerr << "sandpaper: error: --hand-start must be a finite length, mm\n";
    return kExitUsage;
  }
  if (!(r.speed_mm_s > 0) || !(r.amplitude_mm > 0) || !std::isfinite(r.speed_mm_s) || !std::isfinite(r.amplitude_mm)) {
    std::cerr << "sandpaper: error: --speed and --amplitude must be positive (mm/s, mm)\n";
    return kExitUsage;
  }
  if (r.amplitude_mm * 1e-3 > limits.workspace_radius_m) {
    std::cerr << "sandpaper: error: --amplitude " << r.amplitude_mm << " mm leaves the " << limits.workspace_radius_m * 1e3
              << " mm workspace radius of device '" << limits.name << "'\n";
    return kExitUsage;
  }
  return check_trace_folder(r.trace);
}

runtime::DeviceSpec device_spec_of(const PlayRequest& r, const std::string& device) {
  runtime::DeviceSpec spec;
  spec.device = device;
  spec.script.path = r.hand == "circle" ? runtime::HandPath::Circle : runtime::HandPath::Scan;
  spec.script.speed_m_s = r.speed_mm_s * 1e-3;
  spec.script.amplitude_m = r.amplitude_mm * 1e-3;
  spec.script.start_m = r.hand_start_mm * 1e-3;
  spec.hand = !r.device.replay.empty()           ? runtime::SimulatedHand::Replay
              : r.device.hand_model == "dynamic" ? runtime::SimulatedHand::Dynamic
                                                 : runtime::SimulatedHand::Script;
  spec.hand_model = r.device.hand;
  spec.replay_name = r.device.replay;
  spec.watchdog_s = r.guards.watchdog_ms * 1e-3;
  spec.virtual_clock = r.virtual_clock;
  spec.uncalibrated = r.device.uncalibrated;
  // The simulated device records the first second, for the force strip (the rest of the report
  // comes from the telemetry, so a long run does not grow the process).
  const auto first_second = static_cast<std::size_t>(kRecordedSeconds * r.rate_hz);
  spec.record_ticks = r.duration_s == 0 ? first_second
                                        : std::min(static_cast<std::size_t>(std::llround(r.duration_s * r.rate_hz)), first_second);
  return spec;
}

int prepare_play_device(const calibration::CalibrationSet& set, const std::string& device, PlayRequest& r,
                        runtime::DeviceSpec& spec, const std::string& command, bool* real) {
  spec = device_spec_of(r, device);
  runtime::DeviceChoice choice;
  try {
    choice = runtime::choose_device(set, spec);
  } catch (const runtime::DeviceOpenError& e) {
    std::cerr << "sandpaper " << command << ": " << e.what() << "\n" << e.help;
    return kExitUsage;
  }
  if (real) *real = choice.real;
  const calibration::DeviceCalibration& cal = *set.find_device(choice.calibration);
  if (!choice.warning.empty()) std::cerr << "sandpaper " << command << ": warning: " << choice.warning << "\n";
  apply_emulation(cal, r);
  std::vector<glm::dvec2> positions;
  if (spec.hand == runtime::SimulatedHand::Replay) {
    double replay_duration = 0;
    if (const int rc = load_replay(r.device, r.rate_hz, positions, replay_duration); rc != kExitOk) return rc;
    r.duration_s = replay_duration;
  }
  // Again, now that an emulated device's rate and a replay's length are known; a joystick found on
  // the bus keeps the path it was asked through.
  const std::string family = choice.family;
  const std::string through = family == "hidraw" || family == "evdev" ? (spec.through.empty() ? device : spec.through) : "";
  spec = device_spec_of(r, choice.calibration);
  spec.through = through;
  spec.replay_positions_m = std::move(positions);
  if (choice.real) {
    // A real joystick: its servo rates are checked as the loop starts.
    if (const int rc = check_run_length(r.duration_s, r.rate_hz, !r.trace.empty()); rc != kExitOk) return rc;
    return check_trace_folder(r.trace);
  }
  return check_play_request(r, runtime::limits_of(cal));
}

int open_play_device(const calibration::CalibrationSet& set, runtime::DeviceSpec spec, runtime::OpenedDevice& out,
                     const std::string& command) {
  try {
    out = runtime::open_device(set, std::move(spec));
  } catch (const runtime::DeviceOpenError& e) {
    std::cerr << "sandpaper " << command << ": " << e.what() << "\n" << e.help;
    return kExitUsage;
  }
  return kExitOk;
}

namespace {

int play_on_sim(const schema::PatchProgram& prog, runtime::OpenedDevice& opened, const calibration::PsychophysicalMap& map,
                const PlayRequest& r, const Swaps& swaps) {
  const runtime::DeviceLimits& limits = opened.device->limits();
  const bool until_stopped = r.duration_s == 0;
  const runtime::ServoConfig cfg = servo_config_of(r);
  runtime::RecordingDevice& joystick = *opened.recording;
  // Built before anything is printed: a program the evaluator refuses is a usage error.
  auto source = runtime::patch_source_for(joystick, borrowed(prog));

  if (!r.json) {
    const std::string how_long = until_stopped ? std::string("until Ctrl-C") : fmt::format("for {:g} s", cfg.duration_s);
    std::cout << fmt::format("playing {} on {}: {:g} Hz {}, hand {} at {:g} mm/s, {} {:g} mm{}\n", prog.name, limits.name,
                             r.rate_hz, how_long, r.hand, r.speed_mm_s, r.hand == "circle" ? "radius" : "turning at +-",
                             r.amplitude_mm, r.virtual_clock ? " (virtual clock)" : "");
    std::cout << "  device   " << opened.description << "\n";
    if (r.emulated) std::cout << "  emulated " << describe_emulation(r) << "\n";
    std::cout << std::flush;
  }
  const std::size_t keep = r.trace.empty() ? 0 : static_cast<std::size_t>(std::llround(cfg.duration_s * r.rate_hz));
  const Played played = play(joystick, std::move(source), cfg, r.virtual_clock, r.live, keep, &prog, swaps);
  const runtime::ServoReport& rep = played.report;
  // Roughness is a property of textures (the map relates a texture's peak lateral force to it);
  // for springs and dampers alone it does not apply.
  const bool textured = prog.max_lateral_force_N > 0;
  const FeltRoughness felt = felt_roughness_of(played, rep, map);
  const double mean_force = played.mean_force_N;

  if (!r.trace.empty()) {
    // From the telemetry ring: what the servo tick published, not the device's own record.
    std::vector<runtime::TickRecord> published;
    published.reserve(played.records.size());
    for (const auto& t : played.records) published.push_back({t.t_s, t.position_m, t.force_N});
    schema::write_file_atomically(r.trace, runtime::format_trace_csv(published));
  }

  if (r.json) {
    nlohmann::json j{{"material", prog.name},
                     {"device", limits.name},
                     {"ticks", rep.ticks},
                     {"rate_hz", rep.rate_hz},
                     {"rate_hz_target", r.rate_hz},
                     {"duration_s", cfg.duration_s},
                     {"period_us", {{"p50", rep.period_p50_us}, {"p99", rep.period_p99_us}, {"max", rep.period_max_us}, {"min", rep.period_min_us}}},
                     {"jitter_us", rep.jitter_us},
                     {"compute_us", {{"p50", rep.compute_p50_us}, {"p99", rep.compute_p99_us}, {"max", rep.compute_max_us}}},
                     {"overruns", rep.overruns},
                     {"stalls", stalls_json(rep)},
                     {"felt_max_lateral_force_N", rep.felt_max_lateral_force_N},
                     {"felt_mean_lateral_force_N", mean_force},
                     {"felt_peak_N", optional_json(played.felt_peak_N)},
                     {"felt_ridge_crossings", played.felt_peak_N ? nlohmann::json(played.ridge_crossings) : nlohmann::json(nullptr)},
                     {"felt_texture_max_N", optional_json(played.felt_texture_max_N)},
                     {"felt_roughness", textured ? nlohmann::json(felt.roughness) : nlohmann::json(nullptr)},
                     {"felt_roughness_from", textured ? nlohmann::json(felt.from) : nlohmann::json(nullptr)},
                     {"roughness_map", map.id},
                     {"compiled_max_lateral_force_N", prog.max_lateral_force_N},
                     {"compiled_roughness", textured ? nlohmann::json(prog.roughness) : nlohmann::json(nullptr)},
                     {"clamped_ticks", rep.clamped_ticks},
                     {"stop_reason", rep.stop_reason},
                     {"stop_cause", runtime::stop_cause_name(rep.stop_cause)},
                     {"realtime_scheduling", rep.realtime_scheduling},
                     {"memory_locked", rep.memory_locked},
                     {"servo", {{"spin_margin_us", rep.spin_margin_us},
                                {"deadline_guard_ms", runtime::deadline_guard_s(cfg) * 1e3},
                                {"cpu", rep.cpu >= 0 ? nlohmann::json(rep.cpu) : nlohmann::json(nullptr)}}},
                     {"clock", r.virtual_clock ? "virtual" : "monotonic"},
                     {"player", player_name()},
                     {"hand", {{"path", r.hand}, {"speed_mm_s", r.speed_mm_s}, {"amplitude_mm", r.amplitude_mm}}},
                     {"hand_device", opened.description},
                     {"emulation", r.emulated ? nlohmann::json{{"position_step_mm", r.quantization.position_step_m * 1e3},
                                                               {"force_step_N", {r.quantization.force_step_N[0], r.quantization.force_step_N[1]}},
                                                               {"command_max", r.quantization.command_max},
                                                               {"tables", r.tables == runtime::TableSampling::Hold ? "sample-and-hold" : "interpolate"}}
                                              : nlohmann::json(nullptr)},
                     {"trace", r.trace.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.trace)}};
    // The compiler's warnings travel in the program (compile --json and explain --json show them too).
    j["warnings"] = nlohmann::json::array();
    for (const auto& w : prog.warnings) j["warnings"].push_back({{"code", w.code}, {"message", w.message}});
    std::cout << schema::json_text(j, 2) << "\n";
  } else {
    std::cout << fmt::format("  loop     {} ticks, achieved {:.2f} Hz; period p50 {:.1f} us, p99 {:.1f} us, max {:.1f} us; "
                             "jitter {:.2f} us (sd); overruns {}; {}\n",
                             rep.ticks, rep.rate_hz, rep.period_p50_us, rep.period_p99_us, rep.period_max_us,
                             rep.jitter_us, rep.overruns, stalls_text(rep));
    std::cout << fmt::format("  compute  p50 {:.2f} us, p99 {:.2f} us, max {:.2f} us per tick\n", rep.compute_p50_us,
                             rep.compute_p99_us, rep.compute_max_us);
    // Only a texture has a compiled maximum lateral force to compare with; force laws have none.
    const std::string compiled = textured ? fmt::format(" (texture compiled {:.4f} N)", prog.max_lateral_force_N) : "";
    std::cout << fmt::format("  felt     max force {:.4f} N{}, mean {:.4f} N, clamped ticks {}\n", rep.felt_max_lateral_force_N,
                             compiled, mean_force, rep.clamped_ticks);
    if (played.felt_peak_N)
      std::cout << fmt::format("  felt     peak {:.4f} N: the mean over {} ridge crossings of each one's largest |F| "
                               "(explain's felt at speed)\n",
                               *played.felt_peak_N, played.ridge_crossings);
    if (textured)
      std::cout << fmt::format("  percept  felt roughness {} predicted from the texture's felt {} ({}; compiled {})\n",
                               schema::roughness_text(felt.roughness),
                               played.felt_peak_N ? "peak" : played.felt_texture_max_N ? "maximum force" : "maximum force (all terms)",
                               map.id, schema::roughness_text(prog.roughness));
    else
      std::cout << "  percept  no texture: the roughness map does not apply\n";
    auto span = static_cast<std::size_t>(std::llround(0.256 * r.rate_hz));
    std::cout << "  |F|      " << force_strip(joystick.records(), std::max(rep.felt_max_lateral_force_N, 1e-9), 64, span)
              << "  (first 256 ms; bar height 0 to " << fmt::format("{:.3g}", rep.felt_max_lateral_force_N) << " N)\n";
    std::cout << "  servo    " << (r.virtual_clock ? "virtual clock" : rep.realtime_scheduling ? "SCHED_FIFO, memory locked"
                                                                     : "normal priority (SCHED_FIFO not permitted here)")
              << (rep.cpu >= 0 ? fmt::format(", pinned to CPU {}", rep.cpu) : "")
              << "; stopped: " << rep.stop_reason << "\n";
    if (!r.trace.empty()) std::cout << "  trace    " << r.trace << " (" << played.records.size() << " ticks)\n";
  }
  return exit_status_of(rep);
}

// A device a person holds (USB HID PID through libusb or hidraw, an input event node): played, given
// back, then reported.
int play_on_held(const schema::PatchProgram& program, runtime::OpenedDevice& opened, const PlayRequest& r,
                 const Swaps& swaps) {
  const runtime::ServoConfig cfg = servo_config_of(r);
  const auto& info = *opened.usb;
  const std::string& device_name = opened.calibration;
  try {
    runtime::HeldDevice& joystick = *opened.held;
    runtime::validate_config(cfg, joystick.limits());
    auto source = runtime::patch_source_for(joystick, borrowed(program));
    const std::string usb_ids = runtime::usb_ids(info.vendor_id, info.product_id);
    if (!r.json)
      std::cout << fmt::format("playing {} on {} ({}{}): {:g} Hz {}\n", program.name, device_name, usb_ids,
                               opened.node.empty() ? std::string() : " through " + opened.node, r.rate_hz,
                               r.duration_s == 0 ? std::string("until Ctrl-C") : fmt::format("for {:g} s", r.duration_s))
                << std::flush;
    const std::size_t keep = r.trace.empty() ? 0 : static_cast<std::size_t>(std::llround(cfg.duration_s * r.rate_hz));
    // Through play(): Ctrl-C / SIGTERM stop the loop with zero force, and the device is given back below.
    // A device lost and found back at its port is named a reset by the host (LiveServo::join_nonrt).
    Played played = play(joystick, std::move(source), cfg, /*virtual_clock=*/false, /*live=*/r.live, keep, &program, swaps);
    runtime::ServoReport& rep = played.report;
    joystick.close_nonrt();
    if (!r.trace.empty()) {
      // What the tick published (position read, force commanded); the device's own record of what
      // reached it is the device's to keep.
      std::vector<runtime::TickRecord> published;
      published.reserve(played.records.size());
      for (const auto& t : played.records) published.push_back({t.t_s, t.position_m, t.force_N});
      schema::write_file_atomically(r.trace, runtime::format_trace_csv(published));
    }
    // The transport's cause of a device fault (timed out, no device, stalled, ENODEV, ...), empty if none.
    const std::string usb_error = joystick.fault_detail_nonrt();
    const std::string stop = std::string(rep.stop_reason) + " [" + runtime::stop_cause_name(rep.stop_cause) + "]" +
                             (usb_error.empty() ? std::string() : " (" + opened.transport + ": " + usb_error + ")");
    if (r.json) {
      nlohmann::json j{{"material", program.name},
                       {"device", device_name},
                       {"usb", opened.node.empty()
                                   ? nlohmann::json{{"id", usb_ids}, {"bus", info.bus}, {"address", info.address}, {"transport", opened.transport}}
                                   : nlohmann::json{{"id", usb_ids}, {"node", opened.node}, {"transport", opened.transport}}},
                       {"ticks", rep.ticks},
                       {"rate_hz", rep.rate_hz},
                       {"rate_hz_target", r.rate_hz},
                       {"duration_s", cfg.duration_s},
                       {"period_us", {{"p50", rep.period_p50_us}, {"p99", rep.period_p99_us}, {"max", rep.period_max_us}, {"min", rep.period_min_us}}},
                       {"overruns", rep.overruns},
                       {"stalls", stalls_json(rep)},
                       {"felt_max_lateral_force_N", rep.felt_max_lateral_force_N},
                       {"felt_mean_lateral_force_N", played.mean_force_N},
                       {"felt_peak_N", optional_json(played.felt_peak_N)},
                       {"felt_ridge_crossings", played.felt_peak_N ? nlohmann::json(played.ridge_crossings) : nlohmann::json(nullptr)},
                       {"compiled_max_lateral_force_N", program.max_lateral_force_N},
                       {"clamped_ticks", rep.clamped_ticks},
                       {"stop_reason", rep.stop_reason},
                       {"stop_cause", runtime::stop_cause_name(rep.stop_cause)},
                       {"usb_error", usb_error.empty() ? nlohmann::json(nullptr) : nlohmann::json(usb_error)},
                       {"realtime_scheduling", rep.realtime_scheduling},
                       {"memory_locked", rep.memory_locked},
                       {"clock", "monotonic"},
                       {"clock_start_ns", rep.clock_start_ns},
                       {"player", player_name()},
                       {"trace", r.trace.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.trace)}};
      std::cout << schema::json_text(j, 2) << "\n";
    } else {
      std::cout << fmt::format("  loop     {} ticks, achieved {:.2f} Hz; period p99 {:.1f} us; overruns {}; {}\n", rep.ticks,
                               rep.rate_hz, rep.period_p99_us, rep.overruns, stalls_text(rep))
                << fmt::format("  felt     max force {:.4f} N{}, clamped ticks {}\n", rep.felt_max_lateral_force_N,
                               played.felt_peak_N ? fmt::format(", peak {:.4f} N over {} ridge crossings", *played.felt_peak_N,
                                                                played.ridge_crossings)
                                                  : std::string(),
                               rep.clamped_ticks)
                << "  servo    " << (rep.realtime_scheduling ? "SCHED_FIFO, memory locked" : "normal priority (SCHED_FIFO not permitted here)")
                << "; stopped: " << stop << "\n";
      if (!r.trace.empty()) std::cout << "  trace    " << r.trace << " (" << played.records.size() << " ticks)\n";
    }
    return exit_status_of(rep);
  } catch (const std::invalid_argument& e) {
    std::cerr << "sandpaper: error: " << e.what() << "\n";
    return kExitUsage;
  }
}

}  // namespace

int play_patch(const schema::PatchProgram& program, runtime::OpenedDevice& device,
               const calibration::PsychophysicalMap& roughness_map, const PlayRequest& r, const Swaps& swaps) {
  // Forces are compiled against a device's command scale (thesis 7.6.3): another device's program
  // would push with the wrong strength.
  if (program.device != device.calibration) {
    std::cerr << "sandpaper: error: the patch was compiled for device '" << program.device << "', not '" << device.calibration
              << "'; recompile it with --device " << device.calibration << "\n";
    return kExitUsage;
  }
  if (device.held != nullptr) return play_on_held(program, device, r, swaps);
  return play_on_sim(program, device, roughness_map, r, swaps);
}

}  // namespace sandpaper::cli
