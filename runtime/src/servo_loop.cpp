#include "sandpaper/runtime/servo_loop.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include <sched.h>

#include "sandpaper/runtime/tick_timing.hpp"

namespace sandpaper::runtime {
namespace {

// Thesis 3.3.3: 900 Hz was the joystick's rate and textures degrade below about 1 kHz; above
// 10 kHz no haptic device we target can follow.
constexpr double kMinRateHz = 900.0;
constexpr double kMaxRateHz = 10000.0;
constexpr double kNsPerS = 1e9;

StopCause read_fault_cause(DeviceFault fault) noexcept {
  switch (fault) {
    case DeviceFault::ReadTimedOut: return StopCause::DeviceReadTimeout;
    case DeviceFault::Unplugged: return StopCause::DeviceUnplugged;
    case DeviceFault::WriteFailed: return StopCause::DeviceWriteFailed;
    case DeviceFault::None:
    case DeviceFault::ReadFailed: break;
  }
  return StopCause::DeviceReadFailed;
}

StopCause write_fault_cause(DeviceFault fault) noexcept {
  return fault == DeviceFault::Unplugged ? StopCause::DeviceUnplugged : StopCause::DeviceWriteFailed;
}

bool finite(glm::dvec2 v) noexcept { return std::isfinite(v.x) && std::isfinite(v.y); }

std::string hz(double rate) {
  std::ostringstream text;
  text << rate << " Hz";
  return text.str();
}

// Differentiates a sampled signal and smooths it with a first-order (RC) low-pass. The gain uses
// the measured interval, so a late tick's longer step is weighted as the time it really spanned.
class FilteredDerivative {
 public:
  explicit FilteredDerivative(double cutoff_hz) noexcept : rc_s_(1.0 / (2.0 * std::numbers::pi * cutoff_hz)) {}
  // Returns the new estimate; keeps the old one if time did not advance (nothing to divide by).
  glm::dvec2 update(glm::dvec2 previous, glm::dvec2 current, double dt_s) noexcept {
    if (dt_s > 0) {
      const double gain = dt_s / (dt_s + rc_s_);
      value_ += gain * ((current - previous) / dt_s - value_);
    }
    return value_;
  }
  glm::dvec2 value() const noexcept { return value_; }

 private:
  double rc_s_;
  glm::dvec2 value_{0, 0};
};

// Holds the force magnitude to the device maximum without turning it.
// Whole command steps per axis; toward zero where rounding would pass the maximum force.
glm::dvec2 command_of(glm::dvec2 force, const CommandQuantum& c, double max_force_N) noexcept {
  glm::dvec2 out = force;
  for (int a = 0; a < 2; ++a) {
    const double step = c.step_N[a];
    if (!(step > 0)) continue;
    const double cap = c.max_steps > 0 ? static_cast<double>(c.max_steps) : 1e15;
    out[a] = std::clamp(std::round(force[a] / step), -cap, cap) * step;
  }
  if (std::hypot(out.x, out.y) > max_force_N)
    for (int a = 0; a < 2; ++a)
      if (c.step_N[a] > 0) out[a] = std::trunc(force[a] / c.step_N[a]) * c.step_N[a];
  return out;
}

// Exactly: the scaled force's magnitude can round a few ulp above the maximum (10.000000000000002 N
// on a 10 N device), so it is stepped down by one ulp at a time until it is not above it.
glm::dvec2 limit_magnitude(glm::dvec2 force, double max_force_N, bool& clamped) noexcept {
  const double magnitude = std::hypot(force.x, force.y);
  clamped = magnitude > max_force_N;
  if (!clamped) return force;
  glm::dvec2 out = force * (max_force_N / magnitude);
  constexpr double kOneUlpLess = 1.0 - 0x1p-53;
  for (int i = 0; i < 64 && std::hypot(out.x, out.y) > max_force_N; ++i) out *= kOneUlpLess;
  return out;
}

// 0 plays until stopped (the loop's counter cannot reach this in any lifetime).
std::uint64_t tick_count(const ServoConfig& config) {
  if (config.duration_s == 0) return UINT64_MAX;
  return static_cast<std::uint64_t>(std::llround(config.duration_s * config.rate_hz));
}

}  // namespace

double deadline_guard_s(const ServoConfig& config) noexcept {
  return config.deadline_guard_periods > 0 ? config.deadline_guard_periods / config.rate_hz : kDefaultDeadlineGuardS;
}

const char* stop_cause_name(StopCause cause) noexcept {
  switch (cause) {
    case StopCause::Completed: return "completed";
    case StopCause::ForceNotFinite: return "force_not_finite";
    case StopCause::PositionNotFinite: return "position_not_finite";
    case StopCause::DeviceReadFailed: return "device_read_failed";
    case StopCause::DeviceReadTimeout: return "device_read_timeout";
    case StopCause::DeviceUnplugged: return "device_unplugged";
    case StopCause::DeviceWriteFailed: return "device_write_failed";
    case StopCause::DeadlineMissed: return "deadline_missed";
    case StopCause::VelocityLimit: return "velocity_limit";
    case StopCause::StopRequested: return "stop_requested";
    case StopCause::DeviceReset: return "device_reset";
  }
  return "completed";
}

// The first four are the texts reports carried before the causes had names; they stay.
const char* stop_cause_text(StopCause cause) noexcept {
  switch (cause) {
    case StopCause::Completed: return "completed";
    case StopCause::ForceNotFinite: return "non-finite force";
    case StopCause::PositionNotFinite: return "non-finite position";
    case StopCause::DeviceReadFailed: return "device read failed";
    case StopCause::DeviceReadTimeout: return "device read timed out";
    case StopCause::DeviceUnplugged: return "device unplugged";
    case StopCause::DeviceWriteFailed: return "device write failed";
    case StopCause::DeadlineMissed: return "servo deadline missed";
    case StopCause::VelocityLimit: return "velocity limit exceeded";
    case StopCause::StopRequested: return "stopped by signal";
    case StopCause::DeviceReset: return "device reset (it left the bus and came back)";
  }
  return "completed";
}

void validate_config(const ServoConfig& config, const DeviceLimits& limits) {
  const double rate = config.rate_hz;
  if (!std::isfinite(rate) || rate < kMinRateHz || rate > kMaxRateHz)
    throw std::invalid_argument("servo rate " + hz(rate) + " is outside the allowed range " + hz(kMinRateHz) +
                                " to " + hz(kMaxRateHz));
  if (rate < limits.min_rate_hz || rate > limits.max_rate_hz)
    throw std::invalid_argument("servo rate " + hz(rate) + " is outside the range device \"" + limits.name +
                                "\" supports, " + hz(limits.min_rate_hz) + " to " + hz(limits.max_rate_hz));
  if (!std::isfinite(config.duration_s) || config.duration_s < 0)
    throw std::invalid_argument("servo duration must be a finite number of seconds, 0 to play until stopped");
  if (config.duration_s == 0 && config.stop_request == nullptr)
    throw std::invalid_argument("a servo run until stopped (duration 0) needs a stop request to end it");
  if (config.duration_s > 0 && std::llround(config.duration_s * rate) < 1)
    throw std::invalid_argument("servo duration is shorter than one servo period");
  if (!std::isfinite(config.velocity_cutoff_hz) || config.velocity_cutoff_hz <= 0)
    throw std::invalid_argument("velocity filter cutoff must be a positive, finite frequency in Hz");
  if (!std::isfinite(config.ramp_s) || config.ramp_s < 0)
    throw std::invalid_argument("force ramp must be a finite, non-negative time in seconds");
  if (!(config.velocity_hold_s >= 0) || !std::isfinite(config.velocity_hold_s))
    throw std::invalid_argument("velocity hold must be a finite time of 0 s or more");
  if (!(config.velocity_limit_m_s > 0))
    throw std::invalid_argument("velocity limit must be a positive speed in m/s");
  if (!(config.deadline_guard_periods >= 0) || !std::isfinite(config.deadline_guard_periods))
    throw std::invalid_argument("deadline guard must be a finite number of servo periods, 0 for 50 ms");
  if (!(config.spin_margin_s >= 0) || config.spin_margin_s > 1.0 / rate)
    throw std::invalid_argument("spin margin must be between 0 and one servo period (" +
                                std::to_string(1e6 / rate) + " us at " + hz(rate) + ")");
  if (config.cpu < -1 || config.cpu >= CPU_SETSIZE)
    throw std::invalid_argument("CPU " + std::to_string(config.cpu) + " does not exist");
  if (config.cpu >= 0) {
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    if (sched_getaffinity(0, sizeof allowed, &allowed) == 0 && !CPU_ISSET(config.cpu, &allowed)) {
      std::string list;
      for (int c = 0; c < CPU_SETSIZE; ++c)
        if (CPU_ISSET(c, &allowed)) list += (list.empty() ? "" : ", ") + std::to_string(c);
      throw std::invalid_argument("CPU " + std::to_string(config.cpu) + " is not one this process may run on (" + list + ")");
    }
  }
}

namespace {
// A step that is not a finite number of newtons would turn every command into NaN or infinity.
void validate_quantum(const CommandQuantum& q, const DeviceLimits& limits) {
  for (int a = 0; a < 2; ++a)
    if (!std::isfinite(q.step_N[a]) || q.step_N[a] < 0)
      throw std::invalid_argument("device \"" + limits.name + "\" gives a command step of " +
                                  std::to_string(q.step_N[a]) + " N on axis " + (a == 0 ? "x" : "y") +
                                  ": a step is a finite force of 0 N (continuous) or more; check its device file");
  if (q.max_steps < 0)
    throw std::invalid_argument("device \"" + limits.name + "\" gives a largest command of " +
                                std::to_string(q.max_steps) + " steps: 0 (none) or more");
}
}  // namespace

ServoReport run_servo_loop(Device& device, ForceSource& source, ServoClock& clock,
                           const ServoConfig& config) {
  const DeviceLimits& limits = device.limits();
  validate_config(config, limits);
  // The device's own commands (an emulated joystick's whole steps), asked once, before the first tick.
  const CommandQuantum quantum = device.command_quantum();
  validate_quantum(quantum, limits);
  const bool quantized = quantum.step_N[0] > 0 || quantum.step_N[1] > 0;
  const std::uint64_t ticks = tick_count(config);
  const double period_ns = kNsPerS / config.rate_hz;

  // The only allocations of the run, sized by the period and not by the run's length.
  TickTimingStats periods(period_ns);
  TickTimingStats compute(period_ns);
  const double stall_ns = kStallPeriods * period_ns;

  ServoReport report;
  StopCause stop = StopCause::Completed;
  FilteredDerivative velocity(config.velocity_cutoff_hz);
  FilteredDerivative acceleration(config.velocity_cutoff_hz);
  HandState hand;
  std::uint64_t played = 0;
  std::int64_t first_start = 0, previous_start = 0;
  // The last position differentiated, and the tick that read it.
  glm::dvec2 sampled_position{0, 0};
  std::int64_t sampled_start = 0;
  const auto hold_ns = static_cast<std::int64_t>(config.velocity_hold_s * kNsPerS);
  const double velocity_limit_sq = config.velocity_limit_m_s * config.velocity_limit_m_s;
  const double max_late_ns = deadline_guard_s(config) * kNsPerS;

  const std::int64_t start = clock.now_ns();
  report.clock_start_ns = start;
  for (std::uint64_t k = 0; k < ticks && stop == StopCause::Completed; ++k) {
    // Deadlines count from the start, not from the last tick, so a late tick never shifts the rest.
    const std::int64_t deadline = start + static_cast<std::int64_t>(std::llround(static_cast<double>(k) * period_ns));
    clock.sleep_until_ns(deadline);
    const std::int64_t tick_start = clock.now_ns();
    const auto late_ns = static_cast<double>(tick_start - deadline);
    const bool overrun = late_ns > 0.5 * period_ns;
    if (overrun) ++report.overruns;
    if (k == 0) first_start = tick_start;
    const std::int64_t tick_period_ns = k == 0 ? 0 : tick_start - previous_start;
    if (k > 0) {
      periods.add_rt(tick_period_ns);
      if (static_cast<double>(tick_period_ns) > stall_ns) {
        ++report.stalls;
        report.longest_stall_us = std::max(report.longest_stall_us, static_cast<double>(tick_period_ns) * 1e-3);
      }
    }
    const double dt_s = static_cast<double>(tick_period_ns) / kNsPerS;
    const double t_s = static_cast<double>(tick_start - start) / kNsPerS;
    ++played;

    // Each check below decides this tick's force; any fault makes it exactly zero and stops.
    glm::dvec2 position{0, 0};
    glm::dvec2 sent{0, 0};
    if (config.stop_request != nullptr && config.stop_request->load(std::memory_order_relaxed)) {
      stop = StopCause::StopRequested;
    } else if (late_ns > max_late_ns) {
      // The handle has held a stale force for deadline_guard_periods: whatever the hand did meanwhile was not seen.
      stop = StopCause::DeadlineMissed;
    } else if (!device.read_position_rt(t_s, position)) {
      stop = read_fault_cause(device.last_fault_rt());
    } else if (!finite(position)) {
      stop = StopCause::PositionNotFinite;
    } else {
      // A held position is not a still hand until velocity_hold_s has passed without a fresh one:
      // until then the estimate is held, and the next fresh position spans the whole gap.
      if (k == 0) {
        sampled_position = position;
        sampled_start = tick_start;
      } else if (device.position_fresh_rt() || tick_start - sampled_start > hold_ns) {
        const double sample_dt_s = static_cast<double>(tick_start - sampled_start) / kNsPerS;
        const glm::dvec2 previous_velocity = velocity.value();
        hand.velocity_m_s = velocity.update(sampled_position, position, sample_dt_s);
        hand.acceleration_m_s2 = acceleration.update(previous_velocity, hand.velocity_m_s, sample_dt_s);
        sampled_position = position;
        sampled_start = tick_start;
      }
      hand.position_m = position;
      if (k == 0) source.reset_rt(hand);  // state starts under the hand's first reported position

      const glm::dvec2 v = hand.velocity_m_s;
      // Checked before evaluating, so a runaway hand does not advance the material's state either.
      const bool too_fast = v.x * v.x + v.y * v.y > velocity_limit_sq;
      glm::dvec2 force = too_fast ? glm::dvec2{0, 0} : source.force_rt(hand, dt_s);
      if (too_fast) {
        stop = StopCause::VelocityLimit;
      } else if (!finite(force)) {
        stop = StopCause::ForceNotFinite;
      } else {
        // Ramp up from zero at start, so a material that pushes hard at the hand's first position
        // does not jolt it; then the clamp, so the ramp never lets more than the maximum through.
        if (config.ramp_s > 0 && t_s < config.ramp_s) {
          force *= t_s / config.ramp_s;
          ++report.ramped_ticks;
        }
        bool clamped = false;
        force = limit_magnitude(force, limits.max_force_N, clamped);
        if (clamped) ++report.clamped_ticks;
        if (quantized) force = command_of(force, quantum, limits.max_force_N);
        sent = force;
      }
    }
    if (stop == StopCause::Completed) {
      if (device.write_force_rt(sent)) {
        report.felt_max_lateral_force_N = std::max(report.felt_max_lateral_force_N, std::hypot(sent.x, sent.y));
      } else {
        stop = write_fault_cause(device.last_fault_rt());
        sent = {0, 0};  // the closing write below commands zero
      }
    } else {
      device.write_force_rt({0, 0});  // same tick as the fault; its own failure changes nothing now
    }
    const std::int64_t tick_compute_ns = clock.now_ns() - tick_start;
    compute.add_rt(tick_compute_ns);
    previous_start = tick_start;
    if (config.telemetry != nullptr) {
      TelemetryRecord record;
      record.tick = k;
      record.t_s = t_s;
      record.period_s = dt_s;
      record.compute_s = static_cast<double>(tick_compute_ns) / kNsPerS;
      record.position_m = position;
      record.force_N = sent;
      record.overrun = overrun;
      config.telemetry->push_rt(record);
    }
  }
  // Whatever ended the run, leave the handle unforced rather than holding the last command.
  device.write_force_rt({0, 0});

  report.ticks = played;
  report.stop_cause = stop;
  report.stop_reason = stop_cause_text(stop);
  if (config.telemetry != nullptr) report.telemetry_dropped = config.telemetry->dropped();
  if (played >= 2 && previous_start > first_start)
    report.rate_hz = static_cast<double>(played - 1) * kNsPerS / static_cast<double>(previous_start - first_start);
  report.period_p50_us = periods.percentile_us(0.50);
  report.period_p99_us = periods.percentile_us(0.99);
  report.period_max_us = periods.max_us();
  report.period_min_us = periods.min_us();
  report.jitter_us = periods.stddev_us();
  report.compute_p50_us = compute.percentile_us(0.50);
  report.compute_p99_us = compute.percentile_us(0.99);
  report.compute_max_us = compute.max_us();
  return report;
}

}  // namespace sandpaper::runtime
