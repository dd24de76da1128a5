#pragma once
// `sandpaper run`'s options for what moves the simulated handle: the scripted hand (default), the
// dynamic hand (--hand-model dynamic, with --hand-mass/--hand-stiffness/--hand-damping), or the
// replay of a recorded trace (--replay trace.csv); and --uncalibrated for a real device no
// calibration file names. docs/RUNTIME.md describes them; the device
// factory (runtime/devices/open_device.hpp) builds the device.
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;  // not <CLI/CLI.hpp>: that header-only library costs every includer seconds to compile
}

#include "sandpaper/runtime/dynamic_hand.hpp"

namespace sandpaper::cli {

struct RunDeviceOptions {
  std::string hand_model = "position";  // "position" or "dynamic"
  runtime::HandModel hand;              // SI; the CLI takes kg, N/m, N*s/m
  std::string replay;                   // trace CSV to play back instead of a scripted hand
  bool uncalibrated = false;            // --uncalibrated: an evdev device without a calibration file may play
};

void add_run_device_options(CLI::App* run, RunDeviceOptions& d);

// Reads the trace to replay; on success sets `duration_s` to the trace's length at `rate_hz` and
// returns 0. Returns kExitBadInput (unreadable or malformed trace) or kExitUsage (a trace recorded at
// another rate: give its rate with --rate), after printing why.
int load_replay(const RunDeviceOptions& d, double rate_hz, std::vector<glm::dvec2>& positions, double& duration_s);

}  // namespace sandpaper::cli
