// sandpaper-play: plays a compiled patch program (.patch) on the simulated joystick or a USB HID PID
// joystick. The runtime alone: it links no compiler, no image library and no statistics, so it
// starts in milliseconds and, with its memory locked for the servo thread, stays small
// (docs/performance.md, "A player that is only a runtime"). `sandpaper run FILE.patch` execs it.
#include <signal.h>
#include <unistd.h>

#include <iostream>

#include <CLI/CLI.hpp>

#include "sandpaper/player/exit_codes.hpp"
#include "sandpaper/player/play.hpp"
#include "sandpaper/player/play_patch.hpp"
#include "sandpaper/player/play_workspace.hpp"
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/schema/patch_io.hpp"
#include "sandpaper/schema/workspace_io.hpp"
#if SANDPAPER_WITH_SHAPES
#include "../scene_run_report.hpp"
#include "sandpaper/shapes/scene_io.hpp"
#endif

namespace {

using namespace sandpaper;

int play_file(const std::string& file, const std::string& device, const std::string& calibration_dir,
              cli::PlayRequest& r, const CLI::App& app, double crossfade_ms) {
  const auto set_dir = calibration_dir.empty() ? calibration::default_calibration_dir() : std::filesystem::path(calibration_dir);
  auto set = calibration::CalibrationSet::load(set_dir);
#if SANDPAPER_WITH_SHAPES
  if (shapes::looks_like_scene_program_file(file)) {
    // A scene is felt through a device of three axes; the only one with a driver is simulated.
    if (device != "sim3d") {
      std::cerr << "sandpaper-play: error: a scene program plays on --device sim3d (the simulated 3-DOF device; "
                   "docs/SHAPES.md), not '" << device << "'\n";
      return cli::kExitUsage;
    }
    const auto scene = shapes::read_scene_program_file(file);  // PatchFormatError: exit 1, below
    if (scene.device != device) {
      std::cerr << "sandpaper: error: " << file << " was compiled for device '" << scene.device << "', not '" << device
                << "'; recompile it with --device " << device << "\n";
      return cli::kExitUsage;
    }
    const auto play = shapes::play_scene_on_sim3d(scene, r.rate_hz, r.duration_s, r.speed_mm_s * 1e-3);
    return cli::report_scene_run(scene, device, play, r.speed_mm_s, r.json) ? cli::kExitOk : cli::kExitBadInput;
  }
#endif
  const bool workspace = schema::looks_like_workspace_program_file(file);
  if (!workspace && !schema::looks_like_patch_file(file)) {
    std::cerr << "sandpaper-play: error: " << file
              << " is not a patch or workspace program; compile it first (sandpaper compile FILE -o FILE.patch, or "
                 "ws.hws -o ws.wsp) or play it with sandpaper run\n";
    return cli::kExitUsage;
  }
  if (workspace) {
    const calibration::DeviceCalibration* dev = set.find_device(device);
    if (device != "sim" || dev == nullptr) {
      std::cerr << "sandpaper: error: device '" << device << "' cannot be played yet; only --device sim runs workspaces\n";
      return cli::kExitUsage;
    }
    const runtime::DeviceLimits limits = runtime::limits_of(*dev);
    const cli::WorkspaceRunOptions ro = cli::workspace_options_of(r, app, crossfade_ms);
    if (const int rc = cli::check_workspace_request(ro, limits); rc != cli::kExitOk) return rc;
    const auto ws = schema::read_workspace_program_file(file);
    for (const auto& p : ws.patches)
      if (p.program->device != device) {
        std::cerr << "sandpaper: error: " << file << " was compiled for device '" << p.program->device << "', not '" << device
                  << "'; recompile it with --device " << device << "\n";
        return cli::kExitUsage;
      }
    return cli::play_workspace_on_sim(ws, set, ro);
  }
  const std::string command = "run --device " + device;
  runtime::DeviceSpec spec;
  if (const int rc = cli::prepare_play_device(set, device, r, spec, command); rc != cli::kExitOk) return rc;
  set.select_device(spec.device);
  const auto program = schema::read_patch_file(file);  // PatchFormatError: exit 1, below
  // A compiled .patch keeps its warnings (e.g. W0320, a provisional map): show them as compiling would.
  for (const auto& w : program.warnings) std::cerr << "warning[" << w.code << "]: " << w.message << "\n";
  if (program.device != spec.device) {
    std::cerr << "sandpaper: error: " << file << " was compiled for device '" << program.device << "', not '" << spec.device
              << "'; recompile it with --device " << spec.device << "\n";
    return cli::kExitUsage;
  }
  runtime::OpenedDevice opened;
  if (const int rc = cli::open_play_device(set, std::move(spec), opened, command); rc != cli::kExitOk) return rc;
  return cli::play_patch(program, opened, set.roughness_map(), r);
}

}  // namespace

int main(int argc, char** argv) {
  // First, before anything that takes time: SIGINT/SIGTERM request a stop. `sandpaper run` blocked
  // them across its exec of this program, so one sent meanwhile is delivered now, to the handler.
  cli::install_run_stop_handlers();
  sigset_t stops;
  sigemptyset(&stops);
  sigaddset(&stops, SIGINT);
  sigaddset(&stops, SIGTERM);
  sigprocmask(SIG_UNBLOCK, &stops, nullptr);

  CLI::App app{"sandpaper-play: play a compiled patch program (.patch) on the simulated joystick or a USB HID PID joystick,\n"
               "or a compiled workspace program (.wsp) on the simulated joystick.\n"
               "The runtime only: compile materials with `sandpaper compile`; `sandpaper run FILE.patch` runs this."};
  std::string file, device = "sim", calibration_dir, library_dir;
  cli::PlayRequest r;
  double crossfade_ms = 2;
  app.add_option("file", file, "patch program (.patch), workspace program (.wsp) or scene program (.sp3, on --device sim3d) to play")->required();
  app.add_option("--device", device, "device the patch was compiled for (sim), or usb: the first HID PID joystick found (through libusb), or hidraw[:PATH]: the same through its hidraw node, or evdev[:PATH]: through its input event node (docs/DEVICES.md)")
      ->capture_default_str();
  app.add_option("--calibration", calibration_dir, "calibration folder (default: $SANDPAPER_CALIBRATION, $SANDPAPER_DATA_DIR/calibration, or the shipped calibration)");
  app.add_option("--library", library_dir, "accepted as `sandpaper run` does; a compiled patch needs no library");
  app.add_option("--crossfade", crossfade_ms, "workspaces: crossfade time at patch edges, ms")->capture_default_str();
  app.add_flag("--json", r.json, "print one JSON object instead of text");
  cli::add_play_options(&app, r);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? cli::kExitOk : cli::kExitUsage;
  }
  r.live = r.live || isatty(STDERR_FILENO);
  try {
    return play_file(file, device, calibration_dir, r, app, crossfade_ms);
  } catch (const schema::PatchFormatError& e) {
    std::cerr << "sandpaper: error: " << e.what() << "\n";
    return cli::kExitBadInput;
  } catch (const calibration::CalibrationError& e) {
    std::cerr << "sandpaper: calibration error: " << e.what() << "\n";
    return cli::kExitUsage;
  } catch (const std::invalid_argument& e) {
    std::cerr << "sandpaper: error: " << e.what() << "\n";
    return cli::kExitUsage;
  } catch (const std::logic_error& e) {
    std::cerr << "sandpaper: internal error (a bug in Sandpaper, please report it): " << e.what() << "\n";
    return cli::kExitInternal;
  } catch (const std::exception& e) {
    std::cerr << "sandpaper: error: " << e.what() << "\n";
    return cli::kExitUsage;
  }
}
