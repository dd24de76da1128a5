#include "sandpaper/runtime/servo_loop.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace sandpaper::runtime {
namespace {

// Thesis 3.3.3: 900 Hz was the joystick's rate and textures degrade below about 1 kHz; above
// 10 kHz no haptic device we target can follow.
constexpr double kMinRateHz = 900.0;
constexpr double kMaxRateHz = 10000.0;
// Bounds the timing arrays allocated before the first tick (10 M ticks = 160 MB).
constexpr double kMaxTicks = 10'000'000.0;
constexpr double kNsPerS = 1e9;

// Strings would allocate when assigned in the tick (most reasons exceed the small-string buffer),
// so the tick reports an enum and the text is attached after the loop.
enum class Stop { Completed, ReadFailed, WriteFailed, NonFiniteForce };

const char* stop_reason_text(Stop stop) noexcept {
  switch (stop) {
    case Stop::Completed: return "completed";
    case Stop::ReadFailed: return "device read failed";
    case Stop::WriteFailed: return "device write failed";
    case Stop::NonFiniteForce: return "non-finite force";
  }
  return "completed";
}

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
glm::dvec2 limit_magnitude(glm::dvec2 force, double max_force_N, bool& clamped) noexcept {
  const double magnitude = std::hypot(force.x, force.y);
  clamped = magnitude > max_force_N;
  return clamped ? force * (max_force_N / magnitude) : force;
}

struct TimingSummary {
  double p50_us = 0, p99_us = 0, max_us = 0, min_us = 0, stddev_us = 0;
};

// Nearest-rank percentiles; reorders `ns`. Runs after the loop, so it may take its time.
TimingSummary summarize(std::vector<std::int64_t>::iterator first, std::vector<std::int64_t>::iterator last) {
  TimingSummary summary;
  const auto count = static_cast<std::size_t>(last - first);
  if (count == 0) return summary;
  const auto us = [](std::int64_t ns) { return static_cast<double>(ns) * 1e-3; };
  double mean = 0;
  for (auto it = first; it != last; ++it) mean += us(*it);
  mean /= static_cast<double>(count);
  double variance = 0;
  for (auto it = first; it != last; ++it) variance += (us(*it) - mean) * (us(*it) - mean);
  summary.stddev_us = std::sqrt(variance / static_cast<double>(count));
  const auto [lowest, highest] = std::minmax_element(first, last);
  summary.min_us = us(*lowest);
  summary.max_us = us(*highest);
  const auto percentile = [&](double fraction) {
    const auto rank = static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(count)));
    const auto nth = first + static_cast<std::ptrdiff_t>(std::max<std::size_t>(rank, 1) - 1);
    std::nth_element(first, nth, last);
    return us(*nth);
  };
  summary.p50_us = percentile(0.50);
  summary.p99_us = percentile(0.99);
  return summary;
}

std::uint64_t tick_count(const ServoConfig& config) {
  return static_cast<std::uint64_t>(std::llround(config.duration_s * config.rate_hz));
}

}  // namespace

void validate_config(const ServoConfig& config, const DeviceLimits& limits) {
  const double rate = config.rate_hz;
  if (!std::isfinite(rate) || rate < kMinRateHz || rate > kMaxRateHz)
    throw std::invalid_argument("servo rate " + hz(rate) + " is outside the allowed range " + hz(kMinRateHz) +
                                " to " + hz(kMaxRateHz));
  if (rate < limits.min_rate_hz || rate > limits.max_rate_hz)
    throw std::invalid_argument("servo rate " + hz(rate) + " is outside the range device \"" + limits.name +
                                "\" supports, " + hz(limits.min_rate_hz) + " to " + hz(limits.max_rate_hz));
  if (!std::isfinite(config.duration_s) || config.duration_s <= 0)
    throw std::invalid_argument("servo duration must be a positive, finite number of seconds");
  const double ticks = config.duration_s * rate;
  if (ticks > kMaxTicks + 0.5)
    throw std::invalid_argument("servo run of " + std::to_string(std::llround(ticks)) +
                                " ticks is longer than the limit of 10000000 ticks");
  if (std::llround(ticks) < 1) throw std::invalid_argument("servo duration is shorter than one servo period");
  if (!std::isfinite(config.velocity_cutoff_hz) || config.velocity_cutoff_hz <= 0)
    throw std::invalid_argument("velocity filter cutoff must be a positive, finite frequency in Hz");
}

ServoReport run_servo_loop(Device& device, ForceSource& source, ServoClock& clock,
                           const ServoConfig& config) {
  const DeviceLimits& limits = device.limits();
  validate_config(config, limits);
  const std::uint64_t ticks = tick_count(config);
  const double period_ns = kNsPerS / config.rate_hz;

  // The only allocations of the run: one timing slot per tick, filled in by the ticks.
  std::vector<std::int64_t> periods_ns(ticks, 0);
  std::vector<std::int64_t> compute_ns(ticks, 0);

  ServoReport report;
  Stop stop = Stop::Completed;
  FilteredDerivative velocity(config.velocity_cutoff_hz);
  FilteredDerivative acceleration(config.velocity_cutoff_hz);
  HandState hand;
  std::uint64_t played = 0;
  std::int64_t first_start = 0, previous_start = 0;

  const std::int64_t start = clock.now_ns();
  for (std::uint64_t k = 0; k < ticks && stop == Stop::Completed; ++k) {
    // Deadlines count from the start, not from the last tick, so a late tick never shifts the rest.
    const std::int64_t deadline = start + static_cast<std::int64_t>(std::llround(static_cast<double>(k) * period_ns));
    clock.sleep_until_ns(deadline);
    const std::int64_t tick_start = clock.now_ns();
    if (static_cast<double>(tick_start - deadline) > 0.5 * period_ns) ++report.overruns;
    if (k == 0) first_start = tick_start;
    periods_ns[k] = k == 0 ? 0 : tick_start - previous_start;
    const double dt_s = static_cast<double>(periods_ns[k]) / kNsPerS;
    const double t_s = static_cast<double>(tick_start - start) / kNsPerS;
    ++played;

    glm::dvec2 position{0, 0};
    if (!device.read_position_rt(t_s, position)) {
      device.write_force_rt({0, 0});
      stop = Stop::ReadFailed;
    } else {
      if (k > 0) {
        const glm::dvec2 previous_velocity = velocity.value();
        hand.velocity_m_s = velocity.update(hand.position_m, position, dt_s);
        hand.acceleration_m_s2 = acceleration.update(previous_velocity, hand.velocity_m_s, dt_s);
      }
      hand.position_m = position;
      if (k == 0) source.reset_rt(hand);  // state starts under the hand's first reported position

      glm::dvec2 force = source.force_rt(hand, dt_s);
      if (!std::isfinite(force.x) || !std::isfinite(force.y)) {
        device.write_force_rt({0, 0});
        stop = Stop::NonFiniteForce;
      } else {
        bool clamped = false;
        force = limit_magnitude(force, limits.max_force_N, clamped);
        if (clamped) ++report.clamped_ticks;
        if (device.write_force_rt(force)) {
          report.max_lateral_force_N = std::max(report.max_lateral_force_N, std::hypot(force.x, force.y));
        } else {
          stop = Stop::WriteFailed;
        }
      }
    }
    compute_ns[k] = clock.now_ns() - tick_start;
    previous_start = tick_start;
  }
  // Whatever ended the run, leave the handle unforced rather than holding the last command.
  device.write_force_rt({0, 0});

  report.ticks = played;
  report.stop_reason = stop_reason_text(stop);
  if (played >= 2 && previous_start > first_start)
    report.rate_hz = static_cast<double>(played - 1) * kNsPerS / static_cast<double>(previous_start - first_start);
  const auto played_end = static_cast<std::ptrdiff_t>(played);
  const TimingSummary period = summarize(periods_ns.begin() + (played >= 2 ? 1 : played_end), periods_ns.begin() + played_end);
  report.period_p50_us = period.p50_us;
  report.period_p99_us = period.p99_us;
  report.period_max_us = period.max_us;
  report.period_min_us = period.min_us;
  report.jitter_us = period.stddev_us;
  const TimingSummary compute = summarize(compute_ns.begin(), compute_ns.begin() + played_end);
  report.compute_p50_us = compute.p50_us;
  report.compute_p99_us = compute.p99_us;
  report.compute_max_us = compute.max_us;
  return report;
}

}  // namespace sandpaper::runtime
