#pragma once
// The servo loop: each tick reads the device, filters velocity and acceleration, evaluates the
// patch program, clamps the force magnitude to the device maximum, writes it, and measures its
// period and compute time. Thesis 3.3.3: 900 Hz; textures degrade below about 1 kHz.
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "sandpaper/runtime/device.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/servo_clock.hpp"
#include "sandpaper/runtime/telemetry.hpp"

namespace sandpaper::runtime {

struct ServoConfig {
  double rate_hz = 1000.0;     // 900 Hz .. 10 kHz (and within the device's limits)
  double duration_s = 2.0;     // how long to play; ticks = round(duration * rate); 0: until stop_request
                               // (which must then be set); memory does not grow with the run's length
  double velocity_cutoff_hz = 50.0;  // first-order low-pass on finite-difference velocity and acceleration
  // Velocity is differentiated between positions the device reported afresh (Device::position_fresh_rt),
  // over the time between them, so positions that arrive in a burst after a late report read as the
  // hand's speed, not as a jump. A device that reports only on change is silent while the hand
  // stands still: after this long without a fresh position the held one counts as a still hand (s).
  double velocity_hold_s = 0.05;
  // Safety (docs/RUNTIME.md, "Stop causes").
  double ramp_s = 0.05;             // the force is scaled by t / ramp_s over the first ramp_s (0: no ramp)
  double velocity_limit_m_s = 2.0;  // filtered hand speed above this stops the loop (VelocityLimit)
  // A tick starting more than this many periods after its deadline stops the loop (DeadlineMissed).
  // 0: 50 ms at the run's rate (50 periods at 1 kHz, 500 at 10 kHz). Measured (docs/performance.md,
  // "Punctual ticks"): a shared virtual machine stalls for up to 26 ms at any rate, so a fixed 50 periods stopped
  // every 10 kHz run within 4 s, while 50 ms passed every run and still ends one whose handle held
  // a stale force for 50 ms.
  double deadline_guard_periods = 0.0;
  // The real clock sleeps to this long before each deadline, then spins to it: the kernel's wake-up
  // latency (tens of us on a VM) lands inside the margin instead of making the tick late. 0: sleep only.
  // Measured in docs/performance.md; the price is a core busy for the margin of every period.
  double spin_margin_s = 20e-6;
  // Pin the servo thread to this CPU (sched_setaffinity); -1: leave it to the scheduler.
  // docs/RUNTIME.md, "An isolated core", gives the isolcpus/nohz_full recipe for labs.
  int cpu = -1;
  // Set (by a signal handler, another thread) to stop the loop at its next tick (StopRequested).
  const std::atomic<bool>* stop_request = nullptr;
  // Where each tick's record goes (never blocks: drops when full), or nullptr.
  TelemetryRing* telemetry = nullptr;
};

// Why the loop stopped, with stable names (stop_cause_name) for reports and scripts, in the manner
// of Force Dimension's DHD_FORCE_OFF_* causes. In every cause but Completed the tick that sees the
// fault writes zero force (or, when the write itself failed, the loop's closing write does) and
// the loop stops.
enum class StopCause {
  Completed,          // "completed": played the whole duration
  ForceNotFinite,     // "force_not_finite": the force source returned NaN or infinity
  PositionNotFinite,  // "position_not_finite": the device reported a NaN or infinite position
  DeviceReadFailed,   // "device_read_failed"
  DeviceReadTimeout,  // "device_read_timeout"
  DeviceUnplugged,    // "device_unplugged"
  DeviceWriteFailed,  // "device_write_failed"
  DeadlineMissed,     // "deadline_missed": a tick started more than the deadline guard after its deadline
  VelocityLimit,      // "velocity_limit": filtered hand speed above velocity_limit_m_s
  StopRequested,      // "stop_requested": stop_request was set (Ctrl-C, SIGTERM)
  // "device_reset": the device left the bus and came back at the same port (a rebooted firmware).
  // The loop itself sees only DeviceUnplugged; the player names a reset after it (usb_port.hpp).
  DeviceReset,
};
// Stable snake_case name ("device_unplugged"); never changes once released.
const char* stop_cause_name(StopCause cause) noexcept;
// The report's human-readable stop_reason ("device unplugged", "stopped by signal").
const char* stop_cause_text(StopCause cause) noexcept;

// Summary of one run. Periods are measured between successive tick starts on the loop's clock.
struct ServoReport {
  std::uint64_t ticks = 0;
  double rate_hz = 0;           // achieved: (ticks - 1) / (last tick start - first tick start)
  double period_p50_us = 0, period_p99_us = 0, period_max_us = 0, period_min_us = 0;
  double jitter_us = 0;         // standard deviation of the period
  double compute_p50_us = 0, compute_p99_us = 0, compute_max_us = 0;
  std::uint64_t overruns = 0;   // ticks that started after their deadline plus half a period
  // Gaps between tick starts longer than kStallPeriods periods: each is one event, however long.
  std::uint64_t stalls = 0;
  double longest_stall_us = 0;  // the longest such gap (0 without stalls)
  std::uint64_t clamped_ticks = 0;   // ticks whose force was limited to the device maximum
  std::uint64_t ramped_ticks = 0;    // ticks whose force was scaled down by the start ramp
  double felt_max_lateral_force_N = 0;  // largest |F| actually written, N
  StopCause stop_cause = StopCause::Completed;
  std::string stop_reason = "completed";  // stop_cause_text(stop_cause), kept for compatibility
  bool realtime_scheduling = false;  // SCHED_FIFO obtained
  bool memory_locked = false;        // mlockall succeeded
  int realtime_error = 0;            // errno of the refused SCHED_FIFO request (0 if granted or not asked)
  std::uint64_t telemetry_dropped = 0;  // records the telemetry ring had no room for
  int cpu = -1;                      // the CPU the servo thread was pinned to, or -1
  double spin_margin_us = 0;         // the clock's spin margin (0 on the virtual clock)
  // The clock's reading at servo time 0, ns: CLOCK_MONOTONIC on the real clock, so tick times
  // (t_s of the telemetry and a trace) compare with other processes' timestamps on this machine.
  std::int64_t clock_start_ns = 0;
};

// A gap between tick starts longer than this many periods is reported as a stall.
inline constexpr double kStallPeriods = 5.0;
// The deadline guard when ServoConfig::deadline_guard_periods is 0.
inline constexpr double kDefaultDeadlineGuardS = 0.05;
// The guard of `config`, in seconds.
double deadline_guard_s(const ServoConfig& config) noexcept;

// Throws std::invalid_argument for a rate outside 900 Hz - 10 kHz or outside the device's limits,
// a negative or non-finite duration, a run shorter than one tick, a run until stopped without a
// stop_request, a non-positive velocity filter cutoff, a negative or non-finite ramp, a
// non-positive velocity limit, a negative deadline guard, a spin margin outside 0 .. one period, or a CPU
// this process may not run on.
void validate_config(const ServoConfig& config, const DeviceLimits& limits);

// Plays `source` on `device` on the calling thread with `clock`; returns when done.
// Everything the ticks need is allocated before the first tick. Stops at the first StopCause; in
// every case a zero force is written once after the last tick.
// Calls validate_config first (and so may throw).
ServoReport run_servo_loop(Device& device, ForceSource& source, ServoClock& clock,
                           const ServoConfig& config);

// Runs run_servo_loop on a new thread (SCHED_FIFO and locked memory when the platform allows it;
// otherwise it runs with normal priority and says so in the report) and joins it. Uses the
// MonotonicClock. Never prints: the caller decides how to report a missing real-time priority.
ServoReport run_servo_thread_nonrt(Device& device, ForceSource& source, const ServoConfig& config);

// The same on a thread the caller does not wait for: start, do other work (drain telemetry, offer
// new materials), then join. Device, source and config (and what it points to) must outlive join.
class ServoThread {
 public:
  ServoThread() = default;
  ~ServoThread();  // joins if still running
  ServoThread(const ServoThread&) = delete;
  ServoThread& operator=(const ServoThread&) = delete;
  // Validates on the caller's thread (throws std::invalid_argument), then starts the loop.
  void start_nonrt(Device& device, ForceSource& source, const ServoConfig& config);
  // True once the loop has returned (join_nonrt then does not wait).
  bool finished() const noexcept { return finished_.load(std::memory_order_acquire); }
  // Waits for the loop; rethrows what it threw. Call once per start.
  ServoReport join_nonrt();

 private:
  struct Impl;
  Impl* impl_ = nullptr;
  std::atomic<bool> finished_{false};
};

}  // namespace sandpaper::runtime
