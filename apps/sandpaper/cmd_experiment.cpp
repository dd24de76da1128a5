// `sandpaper experiment run|resume|analyse` (docs/EXPERIMENTS.md): present a design's stimuli to a
// subject, record the answers, and analyse pooled results into the statistics and maps of Minsky
// 1995 chapters 4-6.
#include <csignal>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <iostream>
#include <set>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli.hpp"
#include "sandpaper/calibration/fit.hpp"
#include "sandpaper/calibration/fit_error.hpp"
#include "sandpaper/experiment/analysis.hpp"
#include "sandpaper/experiment/design.hpp"
#include "sandpaper/experiment/map_install.hpp"
#include "sandpaper/experiment/observer.hpp"
#include "sandpaper/experiment/presenter.hpp"
#include "sandpaper/experiment/results.hpp"
#include "sandpaper/experiment/schedule.hpp"
#include "sandpaper/experiment/session.hpp"
#include "sandpaper/experiment/subject_page.hpp"
#include "sandpaper/experiment/stimuli.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/json_text.hpp"

namespace sandpaper::cli {
namespace {

namespace ex = experiment;

// Set by SIGINT/SIGTERM: the question waiting is answered "stopped", the servo loop stops (zero
// force), and the session ends resumable.
std::atomic<bool> g_stop{false};

void on_stop_signal(int) { g_stop.store(true); }

void install_stop_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: a terminal read returns, and the terminal observer stops
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

// `observer` as written on the command line or recorded in the results; `percept` the design's, whose
// default compile map gives a simulated observer the exponent it was not given.
std::unique_ptr<ex::Observer> make_observer(const ExperimentOptions& eo, const std::string& observer,
                                            const std::string& subject, const ex::Design& design,
                                            const compiler::Compiler& compiler) {
  if (observer == "terminal") return ex::make_terminal_observer(std::cin, std::cerr);
  if (observer == "page") {
    std::string url;
    auto o = ex::make_page_observer(eo.listen, &g_stop, url);
    // The readiness line scripts wait for.
    std::cerr << "subject page: " << url << " (open it full screen on the subject's screen)" << std::endl;
    return o;
  }
  auto spec = ex::parse_simulated_observer(observer);
  if (!spec.dimension.empty() && spec.dimension != design.percept)
    throw ex::DesignError(fmt::format("--observer: the simulated observer judges {}, but the design scales {}; give "
                                      "dimension={} or leave dimension out", spec.dimension, design.percept, design.percept));
  if (!spec.exponent) {
    const auto* map = compiler.calibration().default_compile_map(design.percept);
    spec.exponent = map ? map->slope : 0.76;
    // Recorded with the exponent it used, so a resumed session answers alike.
    spec.text += fmt::format("{}exponent={:g}", spec.text.empty() ? "" : ",", *spec.exponent);
  }
  return ex::make_simulated_observer(spec, subject);
}

// The presenter for `--device sim|usb`; nullptr (after printing why) when none can be made.
std::unique_ptr<ex::Presenter> make_presenter(const ExperimentOptions& eo, const ex::Design& d,
                                              std::string& device_used) {
  ex::PresentOptions po;
  po.rate_hz = d.rate_hz;
  po.ramp_s = d.ramp_s;
  po.hold_s = d.duration_s;
  po.stop = &g_stop;
  po.deadline_guard_periods = eo.guards.deadline_guard_periods;
  po.velocity_limit_m_s = eo.guards.velocity_limit_m_s;
  runtime::HandScript hand;
  hand.path = runtime::HandPath::Scan;
  hand.speed_m_s = d.hand_speed_m_s;
  hand.amplitude_m = d.hand_amplitude_m;
  // --device sim plays the design's device on the simulated joystick (an emulated one with its
  // quantisation); usb, the joystick plugged in, which must be the design's device; hidraw[:PATH]
  // and evdev[:PATH], the design's device through its hidraw or input event node (docs/DEVICES.md).
  const bool hidraw = eo.device == "hidraw" || eo.device.rfind("hidraw:", 0) == 0 || eo.device == "evdev" ||
                      eo.device.rfind("evdev:", 0) == 0;
  if (eo.device != "sim" && eo.device != "usb" && !hidraw) {
    std::cerr << "sandpaper experiment: --device is sim, usb, hidraw[:PATH] or evdev[:PATH] (the design's `device` names the calibration)\n";
    return nullptr;
  }
  runtime::DeviceSpec spec;
  spec.device = eo.device == "usb" || hidraw ? eo.device : d.device;
  spec.simulate = eo.device == "sim";
  spec.script = hand;
  spec.watchdog_s = eo.guards.watchdog_ms * 1e-3;
  spec.virtual_clock = eo.virtual_clock;
  spec.uncalibrated = eo.uncalibrated;
  CommonOptions o;
  o.calibration_dir = eo.common.calibration_dir;
  o.library_dir = eo.common.library_dir;
  const std::string command = "experiment --device " + eo.device;
  if (eo.virtual_clock) {
    // Each presentation is a run of its own on simulated time, on a device the factory opens for it:
    // the design's device, emulated with all its settings where its calibration says so.
    auto set = std::make_shared<const calibration::CalibrationSet>(load_calibration_set(o));
    runtime::DeviceChoice choice;
    try {
      choice = runtime::choose_device(*set, spec);
    } catch (const runtime::DeviceOpenError& e) {
      std::cerr << "sandpaper " << command << ": " << e.what() << "\n" << e.help;
      return nullptr;
    }
    const bool emulated = std::string(choice.family) == "emulated";
    device_used = fmt::format("{} simulated on the virtual clock, hand scanning at {:g} mm/s over +-{:g} mm, {:g} Hz{}",
                              choice.calibration, hand.speed_m_s * 1e3, hand.amplitude_m * 1e3, po.rate_hz,
                              emulated ? ", with its quantisation and table sampling" : "");
    auto open = [set, spec] { return runtime::open_device(*set, spec).device; };
    return std::make_unique<ex::VirtualPresenter>(open, device_used, po);
  }
  auto opened = open_device_for(o, std::move(spec), command);
  if (!opened) return nullptr;
  if (opened->calibration != d.device) {
    std::cerr << fmt::format("sandpaper experiment: the design compiles for device `{}` but the joystick found is `{}`; "
                             "set device = \"{}\" in the design\n", d.device, opened->calibration, opened->calibration);
    return nullptr;
  }
  device_used = opened->real ? opened->calibration + (opened->node.empty() ? " (USB)" : " (USB, through " + opened->node + ")")
                             : fmt::format("{} simulated in real time, hand scanning at {:g} mm/s{}", d.device,
                                           hand.speed_m_s * 1e3, opened->emulation ? ", with its quantisation and table sampling" : "");
  return std::make_unique<ex::LivePresenter>(std::move(opened->device), device_used, po);
}

int report_outcome(const ex::SessionOutcome& out, const std::filesystem::path& dir, bool json) {
  if (json)
    std::cout << schema::json_text(nlohmann::json{{"ok", out.finished},
                                                  {"results", dir.string()},
                                                  {"answered", out.answered},
                                                  {"next_trial", out.next_trial},
                                                  {"trials", out.total},
                                                  {"finished", out.finished},
                                                  {"stopped", out.stopped},
                                                  {"interrupted", out.interrupted},
                                                  {"cause", out.cause}},
                                   2)
              << "\n";
  else if (out.finished)
    std::cout << fmt::format("all {} trials answered; results in {}\n", out.total, dir.string());
  else
    std::cout << fmt::format("{} of {} trials answered; continue with `sandpaper experiment resume {}`\n", out.next_trial,
                             out.total, dir.string());
  return out.interrupted ? kExitBadInput : kExitOk;
}

int run_or_resume(const ExperimentOptions& eo, bool resume) {
  std::filesystem::path dir = resume ? std::filesystem::path(eo.target) : std::filesystem::path(eo.output);
  ex::Design design;
  std::string subject = eo.subject;
  int first = 0;
  std::optional<ex::Results> previous;
  if (resume) {
    previous = ex::read_results(dir);
    design = ex::parse_design(previous->design_text, dir / "design.toml");
    // Material files named by the design are found beside the original design.
    if (!previous->header.design_path.empty()) {
      const auto base = std::filesystem::path(previous->header.design_path).parent_path();
      for (auto& s : design.stimuli)
        if (!s.file.empty()) s.file = base / s.text;
    }
    subject = previous->header.subject;
    first = previous->next_trial();
  } else {
    design = ex::load_design(eo.target);
  }
  CommonOptions o = eo.common;
  o.device = design.device;
  const auto compiler = make_compiler(o);
  const auto stimuli = ex::prepare_stimuli(design, compiler);
  if (design.task == ex::Task::TwoInterval) {
    double most = 0;
    for (double inc : design.increments) most = std::max(most, inc);
    const double need = stimuli.front().force_N * (1 + most);
    if (need > compiler.device().max_force_N)
      throw ex::DesignError(fmt::format("{}: error: the largest comparison needs {:.4g} N, more than device `{}` can produce "
                                        "({:.4g} N); choose a weaker standard or smaller increments",
                                        design.path, need, design.device, compiler.device().max_force_N));
  }
  const auto schedule = ex::make_schedule(design, subject);
  if (resume && first >= static_cast<int>(schedule.size())) {
    std::cout << fmt::format("{}: every trial is answered already ({} of {})\n", dir.string(), first, schedule.size());
    return kExitOk;
  }
  // Resume answers with the observer the results record; another one only when asked for by name.
  std::string observer_text = eo.observer.empty() ? "terminal" : eo.observer;
  std::optional<std::pair<std::string, std::string>> switched;
  if (resume) {
    const std::string recorded = previous->current_observer();
    if (eo.observer.empty() || eo.observer == recorded) observer_text = recorded;
    else if (!eo.switch_observer) {
      std::cerr << fmt::format("sandpaper experiment resume: {}: these results were answered by observer `{}`; resuming "
                               "with `{}` would mix observers in one subject. Leave --observer out to continue with "
                               "`{}`, or add --switch-observer to change it on purpose (the switch is recorded)\n",
                               dir.string(), recorded, eo.observer, recorded);
      return kExitUsage;
    } else switched.emplace(recorded, eo.observer);
  }
  install_stop_handlers();
  auto observer = make_observer(eo, observer_text, subject, design, compiler);
  std::string device_used;
  auto presenter = make_presenter(eo, design, device_used);
  if (!presenter) return kExitUsage;
  std::optional<ex::ResultsWriter> writer;
  if (resume) {
    writer.emplace(ex::ResultsWriter::reopen(dir));
    if (switched)
      writer->append({{"record", "observer-switch"}, {"from", switched->first}, {"to", observer->describe()},
                      {"trial", first}, {"time", ex::utc_now_iso()}});
  } else {
    ex::ResultsHeader h;
    h.design_checksum = design.checksum;
    h.design_path = std::filesystem::absolute(eo.target).lexically_normal().string();
    h.subject = subject;
    h.task = ex::task_name(design.task);
    h.device = design.device;
    h.percept = design.percept;
    h.observer = observer->describe();
    h.started = ex::utc_now_iso();
    h.trials = static_cast<int>(schedule.size());
    writer.emplace(ex::ResultsWriter::create(dir, design, h));
  }
  std::cerr << fmt::format("{}: {} for subject {}, {} trials{} on {}; observer {}\n", design.title, ex::task_name(design.task),
                           subject, schedule.size(), resume ? fmt::format(", resuming at trial {}", first + 1) : "",
                           device_used, observer->describe());
  const auto out = ex::run_session(design, stimuli, schedule, first, *presenter, *observer, *writer, std::cerr);
  return report_outcome(out, dir, eo.common.json);
}

// Set by analyse for print_analysis: the changes a written map makes, one line each.
std::string map_changes_text_;

void print_analysis(const ex::Analysis& a) {
  const auto& j = a.report;
  std::cout << fmt::format("{}: {} subjects, {} runs pooled, {} answers ({} to practice trials, {} to recorded trials), "
                           "{} interruption records\n",
                           a.task, j["subjects"].get<int>(), a.runs.size(), j["records_answered"].get<int>(),
                           j["practice_answered"].get<int>(), j["recorded_answered"].get<int>(), j["interruptions"].get<int>());
  for (const auto& r : j["runs"])
    if (!r["complete"].get<bool>())
      std::cout << fmt::format("  {} (subject {}): {} of {} recorded trials answered, incomplete: {}\n",
                               r["folder"].get<std::string>(), r["subject"].get<std::string>(), r["answered_recorded"].get<int>(),
                               r["recorded_trials"].get<int>(),
                               r["included"].get<bool>() ? "pooled (--include-incomplete)"
                                                         : "left out (finish it with `experiment resume`, or pass --include-incomplete)");
  if (a.magnitude) {
    const auto& m = j["magnitude_estimation"];
    std::cout << (m["felt_vs_compiled_max_rel_diff"].is_null()
                      ? "  felt against compiled force: " + m["felt_vs_compiled"].get<std::string>() + "\n"
                      : fmt::format("  felt against compiled force: largest difference {:.1f} % ({})\n",
                                    100 * m["felt_vs_compiled_max_rel_diff"].get<double>(),
                                    m["felt_vs_compiled"].get<std::string>()));
    const auto& fp = a.magnitude->predictor;
    std::cout << fmt::format("log {} = {:.4f} log {} {} {:.4f}  ({})\n", m.value("percept", std::string("roughness")),
                             m["slope"].get<double>(), fp.name, m["intercept"].get<double>() < 0 ? "-" : "+",
                             std::abs(m["intercept"].get<double>()),
                             fp.unit == "1" ? fp.name + " has no unit" : fp.name + " in " + fp.unit);
    std::cout << fmt::format("  slope {:.4f} (s.e. {:.4f}), intercept s.e. {:.4f}, R^2 {:.4f} (adjusted {:.4f}), s {:.4g}, "
                             "df {}, F {:.4g}\n",
                             m["slope"].get<double>(), m["slope_se"].get<double>(), m["intercept_se"].get<double>(),
                             m["r2"].get<double>(), m["r2_adj"].get<double>(), m["s"].get<double>(), m["df"].get<int>(),
                             m["f"].is_null() ? 0.0 : m["f"].get<double>());
    if (m["period"]["fitted"].get<bool>()) std::cout << "  " << m["period"]["verdict"].get<std::string>() << "\n";
  }
  if (j.contains("sorting")) {
    const auto& s = j["sorting"];
    std::cout << fmt::format("top split (single linkage): {} | {}\n", fmt::join(s["clusters"][0].get<std::vector<std::string>>(), " "),
                             fmt::join(s["clusters"][1].get<std::vector<std::string>>(), " "));
    std::cout << fmt::format("top split (average linkage): {} | {}\n",
                             fmt::join(s["average"]["clusters"][0].get<std::vector<std::string>>(), " "),
                             fmt::join(s["average"]["clusters"][1].get<std::vector<std::string>>(), " "));
  }
  if (j.contains("two_interval")) {
    const auto& t = j["two_interval"];
    auto bound = [](const nlohmann::json& v) { return v.is_null() ? std::string("unbounded") : fmt::format("{:.4f}", v.get<double>()); };
    std::cout << fmt::format("Weber fraction {:.4f} (95 % interval {} to {}), {} trials\n", t["weber_fraction"].get<double>(),
                             bound(t["weber_fraction_interval"][0]), bound(t["weber_fraction_interval"][1]),
                             t["trials"].get<int>());
  }
  if (j.contains("confidence")) {
    const auto& b = j["confidence"]["boundary"];
    if (b.contains("force_at_50_percent")) {
      std::cout << "50 % confidence boundary (logit regression on log force and log period):";
      for (const auto& p : b["force_at_50_percent"])
        std::cout << fmt::format("  {:g} mm: {}", p["period_mm"].get<double>(),
                                 p["force_N"].is_null() ? std::string("-") : fmt::format("{:.3g} N", p["force_N"].get<double>()));
      std::cout << "\n";
    }
  }
  if (j.contains("confidence"))
    for (const auto& s : j["confidence"]["stimuli"])
      std::cout << fmt::format("  {:<16} {:7.3f} N {:6.2f} mm  mean confidence {:5.1f} % (n {})\n", s["stimulus"].get<std::string>(),
                               s["force_N"].get<double>(), s["period_mm"].get<double>(), s["mean_confidence"].get<double>(),
                               s["n"].get<int>());
  for (const auto& p : a.pictures) std::cout << "picture: " << p.string() << "\n";
  if (j.contains("map")) {
    const auto& m = j["map"];
    std::cout << "map: " << m["file"].get<std::string>() << " (" << m["id"].get<std::string>() << ")\n";
    std::cout << fmt::format("  written to {}; compile reads maps from {}{}\n", m["absolute_file"].get<std::string>(),
                             m["maps_read_from"].get<std::string>(),
                             m["read_by_compile"].get<bool>() ? "" : ": NOT read there (see the warning)");
    if (map_changes_text_.empty())
      std::cout << "  changes nothing that compiled before (named levels and library entries of its percept)\n";
    else std::cout << "  what it changes for device " << m["device"].get<std::string>() << ":\n" << map_changes_text_;
  }
}

// Writing into a calibration folder's maps/ must leave it loadable: a second roughness map for the
// same device, or a second map with this id, would make every later compile fail. Refused here,
// naming the file to replace instead. (Overwriting an earlier fit in the same file is fine.)
void refuse_second_device_map(const std::filesystem::path& out, const std::string& device, const std::string& percept,
                              const std::string& id) {
  const auto maps = out.parent_path();
  const auto dir = maps.parent_path();
  std::error_code ec;
  if (maps.filename() != "maps" || !std::filesystem::is_directory(dir / "devices", ec)) return;
  const auto same = [&](const std::filesystem::path& a) {
    return std::filesystem::weakly_canonical(a, ec) == std::filesystem::weakly_canonical(out, ec);
  };
  for (const auto& e : std::filesystem::directory_iterator(maps, ec)) {
    if (e.path().extension() != ".toml" || same(e.path())) continue;
    calibration::PsychophysicalMap m;
    try {
      m = calibration::load_map_file(e.path());
    } catch (const calibration::CalibrationError&) {
      continue;  // the calibration set reports its own broken files
    }
    if (m.id == id)
      throw ex::DesignError(fmt::format("--map-out: map id `{}` is already used by {}; give --map-id another id, or write "
                                        "to that file to replace it", id, e.path().string()));
    if (m.for_device && m.domain_device == device && m.percept == percept)
      throw ex::DesignError(fmt::format("--map-out: device `{}` already has a {} map, {}; write to that file to "
                                        "replace it, or remove it first", device, percept, e.path().string()));
  }
}

// The map text checked as the compiler will read it (shown as `out`), from a temporary file beside it.
calibration::PsychophysicalMap calibration_parse_check(const std::string& text, const std::filesystem::path& out) {
  const auto check = out.parent_path() / (out.filename().string() + ".check.tmp");
  schema::write_file_atomically(check, text);
  try {
    auto m = calibration::load_map_file(check, out.string());
    std::filesystem::remove(check);
    return m;
  } catch (...) {
    std::filesystem::remove(check);
    throw;
  }
}

int analyse(const ExperimentOptions& eo) {
  ex::AnalyseOptions ao;
  ao.allow_mixed_designs = eo.allow_mixed_designs;
  ao.include_incomplete = eo.include_incomplete;
  ao.pictures_dir = eo.pictures;
  auto a = ex::analyse(eo.target, ao);
  for (const auto& w : a.report["warnings"])
    std::cerr << "sandpaper experiment analyse: warning: " << w.get<std::string>() << "\n";
  if (!eo.map_out.empty()) {
    if (!a.magnitude) throw ex::DesignError("--map-out: only a magnitude-estimation study fits a map (this one is " + a.task + ")");
    const std::string percept = a.runs.front().header.percept;
    const auto& x = a.magnitude->predictor;
    std::set<std::string> devices;
    std::vector<std::string> subjects;
    for (const auto& r : a.runs) {
      devices.insert(r.header.device);
      subjects.push_back(r.header.subject);
    }
    if (devices.size() != 1)
      throw ex::DesignError(fmt::format("--map-out: these runs were made on different devices ({}); a map belongs to one",
                                        fmt::join(devices, ", ")));
    CommonOptions o = eo.common;
    o.device = *devices.begin();
    const auto compiler = make_compiler(o);
    const auto* base = compiler.calibration().default_compile_map(percept);
    calibration::MapFileOptions mo;
    const std::filesystem::path out(eo.map_out);
    mo.id = eo.map_id.empty() ? out.stem().string() : eo.map_id;
    refuse_second_device_map(out, *devices.begin(), percept, mo.id);
    mo.percept = percept;
    mo.device = *devices.begin();
    mo.description = "perceived " + percept + " against the " + x.quantity + " on device " + mo.device +
                     ", measured by magnitude estimation (sandpaper experiment)";
    // Ratio-scale 1 at the default map's reference, so a number asks for the force (stiffness, ...)
    // that this device's own subjects judged as the default map's subjects judged it.
    if (base && base->ratio_predictor == x.name) mo.reference_N = base->reference_si;
    const auto& run0 = a.runs.front();
    mo.provenance = fmt::format("fitted by sandpaper experiment analyse on {}: {} subjects ({}), {} answered trials, "
                                "design {} ({}), observers {}",
                                ex::utc_now_iso(), subjects.size(), fmt::join(subjects, ", "), a.magnitude->answered,
                                run0.header.design_path, run0.header.design_checksum, run0.header.observer);
    mo.citation = "magnitude-estimation study in " + eo.target + " (sandpaper experiment run)";
    // Subjects at a joystick; the Weber fraction of the quantity is not what magnitude estimation
    // measures, so the default map's is carried over, saying so.
    mo.apparatus = "joystick";
    if (base && base->weber_fraction && base->ratio_predictor == x.name) {
      mo.weber_fraction = *base->weber_fraction;
      mo.jnd_source = "not measured by this study; carried over from the default map " + base->id + ": " + base->jnd_source;
    }
    if (eo.map_domain == "levels") {
      // The named levels of the percept keep compiling: the domain is widened to their values through
      // this map, and the map says which part its stimuli covered (W0322 beyond them).
      const auto bare = calibration_parse_check(calibration::map_file_text(*a.magnitude, mo), out);
      mo.widen_domain_to = ex::level_values(compiler.calibration(), bare);
    }
    const std::string text = calibration::map_file_text(*a.magnitude, mo);
    const auto written = calibration_parse_check(text, out);
    // What the map changes, compiled for the device with the calibration compile reads, before and after.
    const auto cal_dir = compiler.calibration().directory();
    compiler::CompileOptions co = compiler.options();
    co.device = mo.device;
    auto installed = ex::calibration_with_map(cal_dir, out.filename().string(), text, written);
    const compiler::Compiler after(co, std::make_shared<const compiler::Library>(compiler.library()), std::move(installed));
    const auto changes = ex::map_changes(compiler, after, percept);
    std::filesystem::path check = out.parent_path() / (out.filename().string() + ".check.tmp");
    schema::write_file_atomically(check, text);
    std::filesystem::rename(check, out);
    std::error_code ec;
    const auto maps_dir = std::filesystem::weakly_canonical(std::filesystem::absolute(cal_dir) / "maps", ec);
    const auto out_dir = std::filesystem::weakly_canonical(std::filesystem::absolute(out).parent_path(), ec);
    const bool read = out_dir == maps_dir;
    a.report["map"] = {{"file", out.string()}, {"id", mo.id}, {"device", mo.device}, {"percept", percept},
                       {"predictor", x.name}, {"reference", mo.reference_N}, {"reference_unit", x.unit},
                       {"absolute_file", std::filesystem::absolute(out).lexically_normal().string()},
                       {"maps_read_from", maps_dir.string()}, {"read_by_compile", read},
                       {"domain", eo.map_domain}, {"changes", ex::map_changes_json(changes)}};
    if (x.name == "force") a.report["map"]["reference_N"] = mo.reference_N;
    if (!read)
      std::cerr << fmt::format("sandpaper experiment analyse: warning: the map was written to {}, but compile reads maps "
                               "from {} (the calibration folder: --calibration, $SANDPAPER_CALIBRATION, "
                               "$SANDPAPER_DATA_DIR/calibration, else the shipped one); `compile --device {}` will not use "
                               "it. Write it into that folder, or compile with --calibration naming the folder it is in\n",
                               std::filesystem::absolute(out).lexically_normal().string(), maps_dir.string(), mo.device);
    map_changes_text_ = ex::map_changes_text(changes);
    if (std::any_of(changes.begin(), changes.end(), [](const ex::MapChange& c) { return c.breaks(); }))
      std::cerr << "sandpaper experiment analyse: warning: installing this map breaks what compiled before (listed "
                   "under the map); --map-domain levels keeps the named levels compiling\n";
  }
  if (eo.common.json)
    std::cout << schema::json_text(a.report, 2) << "\n";
  else print_analysis(a);
  return kExitOk;
}

}  // namespace

void add_experiment_command(CLI::App& app, ExperimentOptions& eo) {
  auto* ex = app.add_subcommand("experiment", "present stimuli to a person, record answers, analyse them into maps (docs/EXPERIMENTS.md)");
  ex->require_subcommand(1);
  auto common = [&](CLI::App* sub) {
    sub->add_option("--library", eo.common.library_dir, "library folder, or folders front first as LAB:WORLD (default: $SANDPAPER_LIBRARY_PATH, $SANDPAPER_LIBRARY, $SANDPAPER_DATA_DIR/library, or the shipped library)");
    sub->add_option("--calibration", eo.common.calibration_dir, "calibration folder (default: $SANDPAPER_CALIBRATION, $SANDPAPER_DATA_DIR/calibration, or the shipped calibration)");
    sub->add_flag("--json", eo.common.json, "print one JSON object instead of text");
  };
  auto playing = [&](CLI::App* sub) {
    sub->add_option("--device", eo.device, "sim (the simulated joystick), usb (the first HID PID joystick, through libusb), hidraw[:PATH] (through its hidraw node) or evdev[:PATH] (through its input event node; docs/DEVICES.md); the design names the calibration")->capture_default_str();
    sub->add_option("--observer", eo.observer, "terminal (a person types the answers; run's default), page (the subject's full-screen page) or simulated:exponent=0.76,noise=0.15,seed=3; resume: default the observer the results record");
    sub->add_option("--listen", eo.listen, "--observer page: ADDR:PORT to serve the page on (port 0: any free port)")->capture_default_str();
    sub->add_flag("--virtual-clock", eo.virtual_clock, "simulated joystick only: each stimulus plays on simulated time, at once (simulated observers, tests)");
    sub->add_flag("--uncalibrated", eo.uncalibrated, "with --device evdev[:PATH]: a force-feedback input device no calibration file names, with the uncalibrated-evdev profile (the design's device must be uncalibrated-evdev; docs/DEVICES.md)");
  };
  eo.run = ex->add_subcommand("run", "run a design for one subject, appending every answer to the results folder");
  eo.run->add_option("design", eo.target, "experiment design (.toml)")->required();
  eo.run->add_option("--subject", eo.subject, "subject id (with the design's seed it fixes the trial order)")->required();
  add_guard_options(eo.run, eo.guards);
  eo.run->add_option("-o,--output", eo.output, "results folder to create")->required();
  playing(eo.run);
  common(eo.run);
  eo.resume = ex->add_subcommand("resume", "continue a results folder from its first unanswered trial, in the same order");
  eo.resume->add_option("results", eo.target, "results folder")->required();
  eo.resume->add_flag("--switch-observer", eo.switch_observer, "answer with --observer although the results record another observer (the switch is recorded)");
  playing(eo.resume);
  common(eo.resume);
  eo.analyse = ex->add_subcommand("analyse", "pool results folders and analyse them as the thesis did");
  eo.analyse->alias("analyze");
  eo.analyse->add_option("results", eo.target, "a results folder, or a folder of them")->required();
  eo.analyse->add_option("--map-out", eo.map_out, "magnitude estimation: write the fitted map of the design's percept for the runs' device (calibration/maps/<device>-<percept>.toml)");
  eo.analyse->add_option("--map-id", eo.map_id, "the map's id (default: the file's stem)");
  eo.analyse->add_option("--map-domain", eo.map_domain, "levels: the map's domain is its stimuli widened to the named levels' values, which compile with W0322 beyond the stimuli; stimuli: the stimuli's range only (levels outside it break, as listed)")
      ->check(CLI::IsMember({"levels", "stimuli"}))->capture_default_str();
  eo.analyse->add_option("--pictures", eo.pictures, "folder for the pictures (default: <results>/analysis)");
  eo.analyse->add_flag("--allow-mixed-designs", eo.allow_mixed_designs, "pool runs of different designs");
  eo.analyse->add_flag("--include-incomplete", eo.include_incomplete, "pool subjects who did not answer every trial (left out by default)");
  common(eo.analyse);
}

int cmd_experiment(const ExperimentOptions& eo) {
  try {
    if (eo.run && eo.run->parsed()) return run_or_resume(eo, false);
    if (eo.resume && eo.resume->parsed()) return run_or_resume(eo, true);
    if (eo.analyse && eo.analyse->parsed()) return analyse(eo);
  } catch (const ex::DesignError& e) {
    if (eo.common.json) std::cout << schema::json_text(nlohmann::json{{"ok", false}, {"errors", e.what()}}, 2) << "\n";
    std::cerr << e.what() << (std::string(e.what()).ends_with("\n") ? "" : "\n");
    return kExitBadInput;
  } catch (const calibration::FitError& e) {
    if (eo.common.json) std::cout << schema::json_text(nlohmann::json{{"ok", false}, {"errors", e.what()}}, 2) << "\n";
    std::cerr << "sandpaper experiment analyse: " << e.what() << "\n";
    return kExitBadInput;
  }
  return -1;
}

}  // namespace sandpaper::cli
