#pragma once
// Plays a force source for `sandpaper run`: the servo loop on its real-time thread (or on the
// virtual clock), Ctrl-C / SIGTERM as a stop request, telemetry drained from the lock-free ring
// (live figures on stderr, the records kept for --trace), the real-time note printed once.
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "sandpaper/runtime/live_servo.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::cli {

struct Played {
  runtime::ServoReport report;
  std::vector<runtime::TelemetryRecord> records;  // every tick, from the telemetry ring (when kept)
  double mean_force_N = 0;                        // mean |F| written over every tick of the run
  std::optional<double> felt_peak_N;              // runtime::FeltPeakMeter's, when measured and crossed
  std::size_t ridge_crossings = 0;                // the crossings it averages
  std::optional<double> felt_texture_max_N;       // largest |F| of the texture terms alone at the played positions
};

// A run's hot swaps (run --watch): `poll` is called on this thread about every 20 ms while playing in
// real time, with the host to offer new sources to (LiveServo::patch_source_nonrt builds them for
// the device); a swap blends over `crossfade_s`.
struct Swaps {
  std::function<void(runtime::LiveServo&)> poll;
  double crossfade_s = runtime::SwappableSource::kDefaultCrossfade_s;
};

// Plays `source` on `device` through one runtime::LiveServo host.
// `keep_records`: how many tick records to keep (the run's tick count for --trace, else 0).
// `live`: print a line of figures on stderr once a second while playing (real time only).
// `felt_of`: measure the felt peak of this program's grating after the start ramp (runtime/felt_peak.hpp); may be null.
Played play(runtime::Device& device, std::unique_ptr<runtime::ForceSource> source, runtime::ServoConfig config,
            bool virtual_clock, bool live, std::size_t keep_records, const schema::PatchProgram* felt_of,
            const Swaps& swaps = {});

// Called first thing in main() for `run`: from then on SIGINT/SIGTERM request a stop (the run ends at
// its first tick, exit 0) instead of killing a process that is still loading or compiling.
void install_run_stop_handlers();

// Exit status for a finished run: 0 when it completed or was stopped by a signal, else 1.
int exit_status_of(const runtime::ServoReport& report);

}  // namespace sandpaper::cli
