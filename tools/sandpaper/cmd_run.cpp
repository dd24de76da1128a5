#include <cmath>
#include <iostream>
#include <sstream>

#include <fmt/format.h>
#include <unistd.h>

#include "cli.hpp"
#include "play.hpp"
#include "run_device.hpp"
#include "sandpaper/runtime/owning_source.hpp"
#include "sandpaper/runtime/swappable_source.hpp"
#include "sandpaper/runtime/trace_csv.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/patch_io.hpp"

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

}  // namespace

int cmd_run(const CommonOptions& o, double rate_hz, double duration_s, const std::string& hand, double speed_mm_s,
            double amplitude_mm, const std::string& trace, bool virtual_clock, bool live,
            const RunDeviceOptions& device_options, bool watch) {
  if (watch) {
    if (o.file.empty() || virtual_clock || o.device == "usb" || !device_options.replay.empty() || !trace.empty()) {
      std::cerr << "sandpaper run --watch: watches a material file (.hmat or .patch) played in real time on --device sim, without --trace\n";
      return kExitUsage;
    }
    // Until Ctrl-C: the longest run the servo loop takes (10 million ticks).
    if (duration_s == 0) duration_s = (1e7 - 1) / rate_hz;
  }
  if (o.device == "usb") return cmd_run_usb(o, rate_hz, duration_s);
  std::vector<glm::dvec2> replayed;
  if (!device_options.replay.empty())
    if (const int rc = load_replay(device_options, rate_hz, replayed, duration_s); rc != kExitOk) return rc;
  auto c = make_compiler(o);
  if (o.device != "sim") {
    std::cerr << "sandpaper: error: device '" << o.device << "' cannot be played yet; only --device sim and --device usb run\n";
    return kExitUsage;
  }
  const runtime::DeviceLimits limits = limits_of(c);

  runtime::ServoConfig cfg;
  cfg.rate_hz = rate_hz;
  cfg.duration_s = duration_s;
  try {
    runtime::validate_config(cfg, limits);
  } catch (const std::invalid_argument& e) {
    std::cerr << "sandpaper: error: " << e.what() << "\n";
    return kExitUsage;
  }
  if (!(speed_mm_s > 0) || !(amplitude_mm > 0) || !std::isfinite(speed_mm_s) || !std::isfinite(amplitude_mm)) {
    std::cerr << "sandpaper: error: --speed and --amplitude must be positive (mm/s, mm)\n";
    return kExitUsage;
  }
  if (amplitude_mm * 1e-3 > limits.workspace_radius_m) {
    std::cerr << "sandpaper: error: --amplitude " << amplitude_mm << " mm leaves the " << limits.workspace_radius_m * 1e3
              << " mm workspace radius of device '" << limits.name << "'\n";
    return kExitUsage;
  }

  if (!trace.empty()) {
    // Refuse an unwritable trace before playing, not after.
    auto dir = std::filesystem::path(trace).parent_path();
    if (dir.empty()) dir = ".";
    if (!std::filesystem::is_directory(dir) || access(dir.c_str(), W_OK) != 0) {
      std::cerr << "sandpaper: error: cannot write the trace '" << trace << "': folder " << dir << " does not exist or is not writable\n";
      return kExitUsage;
    }
  }
  auto in = load_input(o, c, /*allow_patch=*/true);
  if (!in) return kExitBadInput;
  const auto& prog = in->program;
  // A compiled .patch keeps its warnings (e.g. W0320, a provisional map): show them as compiling would.
  if (!in->compile)
    for (const auto& w : prog.warnings) std::cerr << "warning[" << w.code << "]: " << w.message << "\n";
  if (prog.device != o.device) {
    std::cerr << "sandpaper: error: " << o.file << " was compiled for device '" << prog.device << "', not '" << o.device
              << "'; recompile it with --device " << o.device << "\n";
    return kExitUsage;
  }

  runtime::HandScript script;
  script.path = hand == "circle" ? runtime::HandPath::Circle : runtime::HandPath::Scan;
  script.speed_m_s = speed_mm_s * 1e-3;
  script.amplitude_m = amplitude_mm * 1e-3;
  auto ticks = static_cast<std::size_t>(std::llround(duration_s * rate_hz));
  // A watched run may last hours: the device records its first minute (the report's mean and strip).
  const auto recorded = watch ? std::min<std::size_t>(ticks, static_cast<std::size_t>(60 * rate_hz)) : ticks;
  const auto device = make_run_device(device_options, limits, script, recorded, replayed);
  runtime::RecordingDevice& joystick = *device;
  runtime::PatchEvaluator evaluator(prog);
  // --watch: the material plays through a hot-swappable source; on every save it is recompiled here,
  // off the servo thread, and handed over with a crossfade. A save that does not compile leaves the
  // last good program playing.
  runtime::SwappableSource swappable(watch ? std::make_unique<runtime::OwningSource<schema::PatchProgram, runtime::PatchEvaluator>>(
                                                 std::make_shared<const schema::PatchProgram>(prog))
                                           : nullptr,
                                     0.02);
  std::function<void()> reload;
  std::error_code mtime_ec;
  auto last_mtime = std::filesystem::last_write_time(o.file, mtime_ec);
  auto next_check = std::chrono::steady_clock::now();
  if (watch) {
    reload = [&] {
      const auto now = std::chrono::steady_clock::now();
      if (now < next_check) return;
      next_check = now + std::chrono::milliseconds(250);
      swappable.collect_retired_nonrt();
      std::error_code ec;
      const auto mtime = std::filesystem::last_write_time(o.file, ec);
      if (ec || mtime == last_mtime) return;
      last_mtime = mtime;
      std::shared_ptr<const schema::PatchProgram> next;
      if (schema::looks_like_patch_file(o.file)) {
        try {
          next = std::make_shared<const schema::PatchProgram>(schema::read_patch_file(o.file));
        } catch (const schema::PatchFormatError& e) {
          std::cerr << "watch: " << o.file << ": " << e.what() << "; the last good program keeps playing\n";
          return;
        }
      } else {
        auto r = c.compile_file(o.file);
        std::cerr << compiler::format_diagnostics(r.diagnostics);
        if (!r.ok()) {
          std::cerr << "watch: " << o.file << " does not compile; the last good program keeps playing\n";
          return;
        }
        next = std::make_shared<const schema::PatchProgram>(std::move(*r.program));
      }
      try {
        swappable.offer_nonrt(std::make_unique<runtime::OwningSource<schema::PatchProgram, runtime::PatchEvaluator>>(next));
        std::cerr << fmt::format("watch: reloaded {}: maximum lateral force {:.4g} N, roughness {:.3g}\n", next->name,
                                 next->max_lateral_force_N, next->roughness);
      } catch (const std::invalid_argument& e) {
        std::cerr << "watch: " << o.file << ": " << e.what() << "; the last good program keeps playing\n";
      }
    };
    std::cerr << "watch: playing " << prog.name << " until Ctrl-C; save " << o.file << " to hear and feel the change\n";
  }
  runtime::ForceSource& playing = watch ? static_cast<runtime::ForceSource&>(swappable) : evaluator;

  if (!o.json)
    std::cout << fmt::format("playing {} on {}: {:g} Hz for {:g} s, hand {} at {:g} mm/s, {} {:g} mm{}\n", prog.name,
                             limits.name, rate_hz, duration_s, hand, speed_mm_s,
                             hand == "circle" ? "radius" : "turning at +-", amplitude_mm,
                             virtual_clock ? " (virtual clock)" : "");
  if (!o.json) std::cout << "  device   " << describe_run_device(device_options) << "\n";
  const Played played = play(joystick, playing, cfg, virtual_clock, live, trace.empty() ? 0 : ticks, reload);
  const runtime::ServoReport& rep = played.report;
  const auto& map = c.calibration().roughness_map();
  // Roughness is a property of textures (the map relates a texture's peak lateral force to it);
  // for springs and dampers alone it does not apply.
  const bool textured = prog.max_lateral_force_N > 0;
  double roughness = map.percept_of(rep.max_lateral_force_N);
  const auto& recs = joystick.records();
  double mean_force = 0;
  for (const auto& r : recs) mean_force += std::hypot(r.force_N.x, r.force_N.y);
  if (!recs.empty()) mean_force /= static_cast<double>(recs.size());

  if (!trace.empty()) {
    // From the telemetry ring: what the servo tick published, not the device's own record.
    std::vector<runtime::TickRecord> published;
    published.reserve(played.records.size());
    for (const auto& r : played.records) published.push_back({r.t_s, r.position_m, r.force_N});
    schema::write_file_atomically(trace, runtime::format_trace_csv(published));
  }

  if (o.json) {
    nlohmann::json j{{"material", prog.name},
                     {"device", limits.name},
                     {"ticks", rep.ticks},
                     {"rate_hz", rep.rate_hz},
                     {"rate_hz_target", rate_hz},
                     {"duration_s", duration_s},
                     {"period_us", {{"p50", rep.period_p50_us}, {"p99", rep.period_p99_us}, {"max", rep.period_max_us}, {"min", rep.period_min_us}}},
                     {"jitter_us", rep.jitter_us},
                     {"compute_us", {{"p50", rep.compute_p50_us}, {"p99", rep.compute_p99_us}, {"max", rep.compute_max_us}}},
                     {"overruns", rep.overruns},
                     {"max_lateral_force_N", rep.max_lateral_force_N},
                     {"mean_lateral_force_N", mean_force},
                     {"roughness", textured ? nlohmann::json(roughness) : nlohmann::json(nullptr)},
                     {"roughness_map", map.id},
                     {"compiled_max_lateral_force_N", prog.max_lateral_force_N},
                     {"clamped_ticks", rep.clamped_ticks},
                     {"stop_reason", rep.stop_reason},
                     {"stop_cause", runtime::stop_cause_name(rep.stop_cause)},
                     {"realtime_scheduling", rep.realtime_scheduling},
                     {"clock", virtual_clock ? "virtual" : "monotonic"},
                     {"hand", {{"path", hand}, {"speed_mm_s", speed_mm_s}, {"amplitude_mm", amplitude_mm}}},
                     {"hand_device", describe_run_device(device_options)},
                     {"trace", trace.empty() ? nlohmann::json(nullptr) : nlohmann::json(trace)}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << fmt::format("  loop     {} ticks, achieved {:.2f} Hz; period p50 {:.1f} us, p99 {:.1f} us, max {:.1f} us; "
                             "jitter {:.2f} us (sd); overruns {}\n",
                             rep.ticks, rep.rate_hz, rep.period_p50_us, rep.period_p99_us, rep.period_max_us,
                             rep.jitter_us, rep.overruns);
    std::cout << fmt::format("  compute  p50 {:.2f} us, p99 {:.2f} us, max {:.2f} us per tick\n", rep.compute_p50_us,
                             rep.compute_p99_us, rep.compute_max_us);
    // Only a texture has a compiled maximum lateral force to compare with; force laws have none.
    const std::string compiled = textured ? fmt::format(" (texture compiled {:.4f} N)", prog.max_lateral_force_N) : "";
    std::cout << fmt::format("  felt     max force {:.4f} N{}, mean {:.4f} N, clamped ticks {}\n", rep.max_lateral_force_N,
                             compiled, mean_force, rep.clamped_ticks);
    if (textured)
      std::cout << fmt::format("  percept  roughness {:.3f} predicted from the measured force ({})\n", roughness, map.id);
    else
      std::cout << "  percept  no texture: the roughness map does not apply\n";
    auto span = static_cast<std::size_t>(std::llround(0.256 * rate_hz));
    std::cout << "  |F|      " << force_strip(recs, std::max(rep.max_lateral_force_N, 1e-9), 64, span)
              << "  (first 256 ms; bar height 0 to " << fmt::format("{:.3g}", rep.max_lateral_force_N) << " N)\n";
    std::cout << "  servo    " << (virtual_clock ? "virtual clock" : rep.realtime_scheduling ? "SCHED_FIFO, memory locked"
                                                                   : "normal priority (SCHED_FIFO not permitted here)")
              << "; stopped: " << rep.stop_reason << "\n";
    if (!trace.empty()) std::cout << "  trace    " << trace << " (" << played.records.size() << " ticks)\n";
  }
  return exit_status_of(rep);
}

}  // namespace sandpaper::cli
