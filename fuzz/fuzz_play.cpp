#include "fuzz_play.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "fuzz_support.hpp"
#include "sandpaper/runtime/servo_clock.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"

namespace sandpaper::fuzz {
namespace {
std::string digits17(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
}  // namespace

runtime::ServoReport play_and_check(runtime::ForceSource& source, std::uint32_t variant) {
  runtime::HandScript script;
  script.path = (variant & 1) ? runtime::HandPath::Circle : runtime::HandPath::Scan;
  // 5 mm/s .. 0.8 m/s: slow strokes and fast ones, all below the loop's 2 m/s velocity stop.
  script.speed_m_s = 0.005 * static_cast<double>(1u << ((variant >> 1) % 8));
  script.amplitude_m = 0.01 + 0.005 * static_cast<double>((variant >> 4) % 8);
  runtime::SimJoystick joystick(runtime::sim_device_limits(), script, kPlayedTicks);
  runtime::VirtualClock clock;
  runtime::ServoConfig config;
  config.rate_hz = 1000;
  config.duration_s = kPlayedTicks / config.rate_hz;
  config.ramp_s = 0.005;  // past the ramp after 5 ticks: most ticks play the full force
  const runtime::ServoReport report = runtime::run_servo_loop(joystick, source, clock, config);

  const double limit = joystick.limits().max_force_N;
  for (const auto& tick : joystick.records()) {
    const double fx = tick.force_N.x, fy = tick.force_N.y;
    check(std::isfinite(fx) && std::isfinite(fy), "commanded force not finite at t = " + digits17(tick.t_s) + " s");
    // Exact: the clamp must never let through more than the device's maximum, not by one ulp.
    const double magnitude = std::hypot(fx, fy);
    check(magnitude <= limit, "commanded |F| = " + digits17(magnitude) + " N exceeds the device maximum " +
                                  digits17(limit) + " N");
  }
  check(report.felt_max_lateral_force_N <= limit,
        "report's max_lateral_force_N " + digits17(report.felt_max_lateral_force_N) + " N exceeds the device maximum");
  return report;
}

}  // namespace sandpaper::fuzz
