#pragma once
// The servo loop: each tick reads the device, filters velocity and acceleration, evaluates the
// patch program, clamps the force magnitude to the device maximum, writes it, and measures its
// period and compute time. Thesis 3.3.3: 900 Hz; textures degrade below about 1 kHz.
#include <cstdint>
#include <string>
#include <vector>

#include "sandpaper/runtime/device.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/servo_clock.hpp"

namespace sandpaper::runtime {

struct ServoConfig {
  double rate_hz = 1000.0;     // 900 Hz .. 10 kHz (and within the device's limits)
  double duration_s = 2.0;     // how long to play; ticks = round(duration * rate)
  double velocity_cutoff_hz = 50.0;  // first-order low-pass on finite-difference velocity and acceleration
};

// Summary of one run. Periods are measured between successive tick starts on the loop's clock.
struct ServoReport {
  std::uint64_t ticks = 0;
  double rate_hz = 0;           // achieved: (ticks - 1) / (last tick start - first tick start)
  double period_p50_us = 0, period_p99_us = 0, period_max_us = 0, period_min_us = 0;
  double jitter_us = 0;         // standard deviation of the period
  double compute_p50_us = 0, compute_p99_us = 0, compute_max_us = 0;
  std::uint64_t overruns = 0;   // ticks that started after their deadline plus half a period
  std::uint64_t clamped_ticks = 0;   // ticks whose force was limited to the device maximum
  double max_lateral_force_N = 0;    // largest |F| actually written
  std::string stop_reason = "completed";  // "completed", "device read failed", "device write failed", "non-finite force"
  bool realtime_scheduling = false;  // SCHED_FIFO obtained
};

// Throws std::invalid_argument for a rate outside 900 Hz - 10 kHz or outside the device's limits,
// a non-positive or non-finite duration, a run shorter than one tick or longer than 10 million
// ticks, or a non-positive velocity filter cutoff.
void validate_config(const ServoConfig& config, const DeviceLimits& limits);

// Plays `source` on `device` on the calling thread with `clock`; returns when done.
// Everything the ticks need is allocated before the first tick. Stops at the first device fault or
// non-finite force; in every case a zero force is written once after the last tick.
// Calls validate_config first (and so may throw).
ServoReport run_servo_loop(Device& device, ForceSource& source, ServoClock& clock,
                           const ServoConfig& config);

// Runs run_servo_loop on a new thread (SCHED_FIFO and locked memory when the platform allows it;
// otherwise it runs with normal priority and says so in the report) and joins it. Uses the
// MonotonicClock. Never prints: the caller decides how to report a missing real-time priority.
ServoReport run_servo_thread_nonrt(Device& device, ForceSource& source, const ServoConfig& config);

}  // namespace sandpaper::runtime
