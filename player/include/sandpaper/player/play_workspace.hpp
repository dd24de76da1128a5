#pragma once
// Playing a workspace program (patches placed on a workspace, thesis Appendix B) on the simulated
// joystick: shared by `sandpaper run ws.hws` (which compiles first) and `sandpaper-play ws.wsp`.
#include <optional>
#include <string>

namespace CLI {
class App;  // not <CLI/CLI.hpp>: that header-only library costs every includer seconds to compile
}

#include "sandpaper/player/play_patch.hpp"
#include "sandpaper/runtime/device.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/schema/workspace_program.hpp"

namespace sandpaper::cli {

// Options left unset take workspace defaults: a scan through the centre in the direction that
// crosses the most patches, out to the furthest, for one lap. Units: Hz, s, mm/s, mm, ms.
struct WorkspaceRunOptions {
  double rate_hz = 1000;
  std::optional<double> duration_s;
  std::optional<std::string> hand;
  double speed_mm_s = 50;
  std::optional<double> amplitude_mm;
  double hand_start_mm = 0;
  std::string trace;
  bool virtual_clock = false;
  double crossfade_ms = 2;
  bool live = false;  // live servo figures on stderr once a second
  bool json = false;
  runtime::ServoConfig servo;  // spin margin, deadline guard, CPU (rate and duration are set from the above)
};

// The workspace options of a parsed `run` (or `sandpaper-play`): only what was given on `run` overrides the defaults.
WorkspaceRunOptions workspace_options_of(const PlayRequest& r, const CLI::App& run, double crossfade_ms);

// Checks what can be checked before loading (speed, amplitude, crossfade, a writable trace folder):
// 0, or kExitUsage after printing why.
int check_workspace_request(const WorkspaceRunOptions& ro, const runtime::DeviceLimits& limits);

// "patch 1   \"corduroy\" at 0 mm, 0 mm  size 40 x 40 mm"
std::string patch_line(const schema::WorkspaceProgram& ws, std::size_t i);

// Plays `ws` on the device "sim" of `set` (opened through runtime::open_device) and reports (text,
// or JSON with ro.json).
int play_workspace_on_sim(const schema::WorkspaceProgram& ws, const calibration::CalibrationSet& set,
                          const WorkspaceRunOptions& ro);

}  // namespace sandpaper::cli
