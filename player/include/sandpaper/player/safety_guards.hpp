#pragma once
// The servo loop's safety stops as command-line options, the same for every command that plays a
// device (`run`, `studio`, `experiment run`, `sandpaper-play`): docs/RUNTIME.md "Stop causes".
namespace CLI {
class App;  // not <CLI/CLI.hpp>: that header-only library costs every includer seconds to compile
}

#include "sandpaper/runtime/servo_loop.hpp"

namespace sandpaper::cli {

// Units at the boundary: servo periods, m/s, ms.
struct SafetyGuards {
  double deadline_guard_periods = runtime::ServoConfig{}.deadline_guard_periods;  // 0: 50 ms
  double velocity_limit_m_s = runtime::ServoConfig{}.velocity_limit_m_s;
  double watchdog_ms = 0;  // --device usb: no position, or no force taken, this long stops (0: the device file's)

  // Copies the deadline guard and the velocity limit into a servo configuration.
  void apply(runtime::ServoConfig& config) const {
    config.deadline_guard_periods = deadline_guard_periods;
    config.velocity_limit_m_s = velocity_limit_m_s;
  }
};

// Registers --deadline-guard, --velocity-limit and --watchdog on `command`.
void add_guard_options(CLI::App* command, SafetyGuards& guards);

}  // namespace sandpaper::cli
