// `sandpaper run`: compiles a material (or reads a .patch) and plays it through the runtime-only
// player code (player/). A plain .patch is handed to the `sandpaper-play` executable itself
// (exec_player), so that the playing process maps none of the compiler's libraries.
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>

#include "cli.hpp"
#include "sandpaper/player/play_patch.hpp"
#include "sandpaper/compiler/source_watch.hpp"
#include "sandpaper/runtime/live_servo.hpp"
#include "sandpaper/schema/patch_io.hpp"

namespace sandpaper::cli {

int exec_player(int argc, char** argv) {
  // Beside this executable in a build tree and in an installed bin/ alike.
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return -1;
  const std::string player = (self.parent_path() / "sandpaper-play").string();
  if (access(player.c_str(), X_OK) != 0) return -1;
  std::vector<char*> args;
  args.push_back(const_cast<char*>(player.c_str()));
  for (int i = 2; i < argc; ++i) args.push_back(argv[i]);  // everything after `run`
  args.push_back(nullptr);
  // A Ctrl-C during the exec must not kill the player before it installs its handlers: blocked
  // signals stay blocked (and pending) across exec, and sandpaper-play unblocks them once it has.
  sigset_t stops;
  sigemptyset(&stops);
  sigaddset(&stops, SIGINT);
  sigaddset(&stops, SIGTERM);
  sigprocmask(SIG_BLOCK, &stops, nullptr);
  execv(player.c_str(), args.data());
  const int error = errno;
  sigprocmask(SIG_UNBLOCK, &stops, nullptr);
  std::cerr << "sandpaper: note: cannot start " << player << " (" << std::strerror(error) << "); playing in this process\n";
  return -1;
}

// Without --device, a calibrated joystick that is plugged in plays (through hidraw, else evdev);
// a request only the simulator can follow (a replay, the dynamic hand, the virtual clock, --watch)
// keeps the simulated joystick, as does a machine with no such joystick.
CommonOptions with_default_device(CommonOptions o, const PlayRequest& r, bool watch) {
  if (o.device_given || watch || r.virtual_clock || !r.device.replay.empty() || r.device.hand_model != "position") return o;
  const auto chosen = runtime::default_play_device(load_calibration_set(o));
  if (chosen.device == "sim") return o;
  o.device = chosen.device;
  std::cerr << "sandpaper run: no --device given: playing on " << chosen.found << " (--device " << chosen.device
            << "; --device sim for the simulated joystick)\n";
  return o;
}

int cmd_run(const CommonOptions& given, PlayRequest r, bool watch) {
  const CommonOptions o = with_default_device(given, r, watch);
  r.json = o.json;  // --json is one of the options every command shares
  const std::string command = "run --device " + o.device;
  if (watch && (o.file.empty() || r.virtual_clock || !r.device.replay.empty() || !r.trace.empty())) {
    std::cerr << "sandpaper run --watch: watches a material file (.hmat or .patch) played in real time on --device sim, without --trace\n";
    return kExitUsage;
  }
  // The device is settled first (a USB joystick names the calibration its programs take), the
  // material compiled for it, and only then is the device claimed.
  const auto set = load_calibration_set(o);
  runtime::DeviceSpec spec;
  bool real = false;
  if (const int rc = prepare_play_device(set, o.device, r, spec, command, &real); rc != kExitOk) return rc;
  if (watch && real) {
    std::cerr << "sandpaper run --watch: plays on --device sim; a real joystick plays a material with run, or in the studio\n";
    return kExitUsage;
  }
  CommonOptions co = o;
  co.device = spec.device;
  auto c = make_compiler(co);
  auto in = load_input(co, c, /*allow_patch=*/true);
  if (!in) return kExitBadInput;
  const auto& prog = in->program;
  // A compiled .patch keeps its warnings (e.g. W0320, a provisional map): show them as compiling would.
  if (!in->compile)
    for (const auto& w : prog.warnings) std::cerr << "warning[" << w.code << "]: " << w.message << "\n";
  if (prog.device != spec.device) {
    std::cerr << "sandpaper: error: " << o.file << " was compiled for device '" << prog.device << "', not '" << spec.device
              << "'; recompile it with --device " << spec.device << "\n";
    return kExitUsage;
  }
  runtime::OpenedDevice device;
  if (const int rc = open_play_device(set, std::move(spec), device, command); rc != kExitOk) return rc;
  const auto& map = c.calibration().roughness_map();
  if (!watch) return play_patch(prog, device, map, r);

  // --watch: the material plays through a hot-swappable source; on every save it is recompiled here,
  // off the servo thread, and handed over with a crossfade. A save that does not compile leaves the
  // last good program playing.
  // Saves are noticed by their text, not the file's stamp alone (source_watch.hpp: an editor's
  // truncate-then-write can leave one stamp on both).
  compiler::SourceWatch saved(o.file);
  auto next_check = std::chrono::steady_clock::now();
  Swaps swaps;
  swaps.crossfade_s = 0.02;
  swaps.poll = [&](runtime::LiveServo& host) {
    const auto now = std::chrono::steady_clock::now();
    if (now < next_check) return;
    next_check = now + std::chrono::milliseconds(250);
    host.collect_retired_nonrt();
    if (!saved.changed()) return;
    std::shared_ptr<const schema::PatchProgram> next;
    if (schema::looks_like_patch_file(o.file)) {
      try {
        next = std::make_shared<const schema::PatchProgram>(schema::read_patch_file(o.file));
      } catch (const schema::PatchFormatError& e) {
        std::cerr << "watch: " << o.file << ": " << e.what() << "; the last good program keeps playing\n";
        return;
      }
    } else {
      auto compiled = c.compile_file(o.file);
      std::cerr << compiler::format_diagnostics(compiled.diagnostics);
      if (!compiled.ok()) {
        std::cerr << "watch: " << o.file << " does not compile; the last good program keeps playing\n";
        return;
      }
      next = std::make_shared<const schema::PatchProgram>(std::move(*compiled.program));
    }
    try {
      host.offer_nonrt(host.patch_source_nonrt(next));
      std::cerr << fmt::format("watch: reloaded {}: maximum lateral force {:.4g} N, roughness {:.3g}\n", next->name,
                               next->max_lateral_force_N, next->roughness);
    } catch (const std::invalid_argument& e) {
      std::cerr << "watch: " << o.file << ": " << e.what() << "; the last good program keeps playing\n";
    }
  };
  std::cerr << "watch: playing " << prog.name << " until Ctrl-C; save " << o.file << " to hear and feel the change\n";
  return play_patch(prog, device, map, r, swaps);
}

}  // namespace sandpaper::cli
