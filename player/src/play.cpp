#include "sandpaper/player/play.hpp"

#include <csignal>
#include <cstring>
#include <iostream>
#include <thread>

#include <fmt/format.h>

#include "sandpaper/player/exit_codes.hpp"
#include "sandpaper/runtime/live_servo.hpp"

namespace sandpaper::cli {
namespace {

// Set by the handler, read by the servo tick: a lock-free atomic is all a handler may touch.
std::atomic<bool> stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void request_stop(int) { stop_requested.store(true, std::memory_order_relaxed); }

// Installs the handler for SIGINT and SIGTERM for the run and puts the old ones back after.
class StopOnSignal {
 public:
  // The flag is not cleared here: a signal that came after main() installed the handler early
  // (install_run_stop_handlers) but before playing began must still stop the run, at its first tick.
  StopOnSignal() {
    struct sigaction action{};
    action.sa_handler = request_stop;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
  }
  ~StopOnSignal() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

 private:
  struct sigaction old_int_{};
  struct sigaction old_term_{};
};

// Ticks a ring holds while the reader sleeps between drains: 2^16 is 6.5 s at 10 kHz.
constexpr std::size_t kRealTimeRingRecords = 1 << 16;

void print_live(const runtime::TelemetryReader& reader, std::uint64_t dropped) {
  const auto& last = reader.last();
  std::cerr << fmt::format("live  t {:.1f} s  period p50 {:.0f} us p99 {:.0f} us max {:.0f} us  compute p99 {:.1f} us  "
                           "overruns {}  |F| {:.3f} N (max {:.3f} N){}\n",
                           last.t_s, reader.periods().percentile_us(0.5), reader.periods().percentile_us(0.99),
                           reader.periods().max_us(), reader.compute().percentile_us(0.99), reader.overruns(),
                           std::hypot(last.force_N.x, last.force_N.y), reader.max_force_N(),
                           dropped ? fmt::format("  dropped {}", dropped) : std::string());
}

}  // namespace

void install_run_stop_handlers() {
  struct sigaction action{};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

Played play(runtime::Device& device, std::unique_ptr<runtime::ForceSource> source, runtime::ServoConfig config,
            bool virtual_clock, bool live, std::size_t keep_records, const schema::PatchProgram* felt_of,
            const Swaps& swaps) {
  StopOnSignal signals;
  // The virtual clock runs the loop on this thread as fast as it can, so nothing drains the ring
  // meanwhile: it must hold the whole run.
  const auto ticks = static_cast<std::size_t>(std::llround(config.duration_s * config.rate_hz));
  runtime::LiveServo::Options options;
  options.telemetry_records = virtual_clock && ticks > 0 ? ticks + 1 : kRealTimeRingRecords;
  options.crossfade_s = swaps.crossfade_s;
  runtime::LiveServo host(device, std::move(source), options);
  runtime::TelemetryRing& ring = *host.telemetry();
  runtime::TelemetryReader reader(ring, config.rate_hz, keep_records);
  if (felt_of != nullptr) reader.measure_felt_peak(*felt_of, config.ramp_s);

  Played played;
  if (virtual_clock) {
    config.stop_request = &stop_requested;  // the loop runs on this thread: only the signal's flag can stop it
    played.report = host.run_virtual_nonrt(config);
  } else {
    host.start_nonrt(config);
    auto next_live = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    while (!host.finished()) {
      // A signal that came before the run began stops it at once, one after within this wait.
      if (stop_requested.load(std::memory_order_relaxed)) host.request_stop_nonrt();
      std::this_thread::sleep_for(std::chrono::milliseconds(stop_requested.load(std::memory_order_relaxed) ? 1 : 20));
      reader.drain_nonrt();
      if (swaps.poll) swaps.poll(host);
      if (live && std::chrono::steady_clock::now() >= next_live) {
        print_live(reader, ring.dropped());
        next_live += std::chrono::seconds(1);
      }
    }
    played.report = host.join_nonrt();
    if (!played.report.realtime_scheduling)
      std::cerr << "note: running without real-time priority (SCHED_FIFO refused: "
                << std::strerror(played.report.realtime_error) << "); timing may jitter\n";
  }
  reader.drain_nonrt();
  if (ring.dropped() > 0)
    std::cerr << "warning: the telemetry reader fell behind; " << ring.dropped() << " tick records were dropped\n";
  played.records = reader.kept();
  played.mean_force_N = reader.mean_force_N();
  if (const auto* felt = reader.felt()) {
    played.felt_peak_N = felt->felt_peak_N();
    played.ridge_crossings = felt->crossings();
  }
  played.felt_texture_max_N = reader.felt_texture_max_N();
  return played;
}

int exit_status_of(const runtime::ServoReport& report) {
  const bool fine = report.stop_cause == runtime::StopCause::Completed ||
                    report.stop_cause == runtime::StopCause::StopRequested;
  return fine ? kExitOk : kExitBadInput;
}

}  // namespace sandpaper::cli
