#include "sandpaper/player/safety_guards.hpp"

#include <CLI/CLI.hpp>

namespace sandpaper::cli {

void add_guard_options(CLI::App* command, SafetyGuards& g) {
  command->add_option("--deadline-guard", g.deadline_guard_periods,
                      "stop (deadline_missed) when a tick starts this many servo periods late (0: 50 ms)")
      ->capture_default_str();
  command->add_option("--velocity-limit", g.velocity_limit_m_s,
                      "stop (velocity_limit) when the filtered hand speed exceeds this, m/s (0.01 to 100)")
      ->check(CLI::Range(0.01, 100.0))
      ->capture_default_str();
  command->add_option("--watchdog", g.watchdog_ms,
                      "--device usb: stop (device_read_timeout, device_write_failed) when the joystick sends no position or "
                      "takes no force for this long, ms (0: 50 ms, or twice the device file's [usb] idle_report_period)")
      ->check(CLI::Range(0.0, 60000.0))
      ->capture_default_str();
}

}  // namespace sandpaper::cli
