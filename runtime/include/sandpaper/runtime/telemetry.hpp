#pragma once
// Telemetry that does not touch the tick's timing (docs/RUNTIME.md, "Telemetry"): the servo tick
// pushes one plain record per tick into a lock-free SPSC ring and never waits (a full ring drops
// the record and counts it); a reader on another thread drains it, keeps period and compute-time
// histograms in bins allocated up front, and may keep the records (for a trace file).
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>

#include "sandpaper/runtime/felt_peak.hpp"
#include "sandpaper/runtime/texture_force.hpp"
#include "sandpaper/runtime/spsc_ring.hpp"

namespace sandpaper::runtime {

struct TelemetryRecord {
  std::uint64_t tick = 0;
  double t_s = 0;            // tick start, s since the loop started
  double period_s = 0;       // since the previous tick's start (0 on the first tick)
  double compute_s = 0;      // this tick's read + evaluate + write, s
  glm::dvec2 position_m{0, 0};
  glm::dvec2 force_N{0, 0};  // force written this tick (after ramp and clamp; 0 on a fault)
  bool overrun = false;      // started more than half a period after its deadline
};

// The servo side. push_rt never blocks or allocates.
class TelemetryRing {
 public:
  explicit TelemetryRing(std::size_t capacity_records) : ring_(capacity_records) {}
  void push_rt(const TelemetryRecord& record) noexcept {
    if (!ring_.try_push(record)) dropped_.fetch_add(1, std::memory_order_relaxed);
  }
  bool pop_nonrt(TelemetryRecord& record) noexcept { return ring_.try_pop(record); }
  // Records the ring had no room for (the reader fell behind).
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }
  std::size_t capacity() const noexcept { return ring_.capacity(); }

 private:
  SpscRing<TelemetryRecord> ring_;
  std::atomic<std::uint64_t> dropped_{0};
};

// Fixed-bin histogram of durations: bins of `bin_us` microseconds from 0, the last bin catching
// everything longer. Percentiles are the upper edge of the bin holding that rank.
class DurationHistogram {
 public:
  static constexpr std::size_t kBins = 2000;
  explicit DurationHistogram(double bin_us) noexcept : bin_us_(bin_us) {}
  void add(double seconds) noexcept;
  std::uint64_t count() const noexcept { return count_; }
  double max_us() const noexcept { return max_us_; }
  double mean_us() const noexcept { return count_ ? sum_us_ / static_cast<double>(count_) : 0; }
  // Upper edge (us) of the bin holding the nearest-rank `fraction` percentile; 0 when empty.
  double percentile_us(double fraction) const noexcept;
  void clear() noexcept;

 private:
  double bin_us_;
  std::array<std::uint64_t, kBins> bins_{};
  std::uint64_t count_ = 0;
  double sum_us_ = 0, max_us_ = 0;
};

// The reader side: drains the ring into histograms and running figures, and optionally keeps every
// record (reserve `keep_records` up front; beyond that they are counted but not kept).
class TelemetryReader {
 public:
  // `rate_hz` sizes the period bins (period / 100 each, so 2000 bins reach 20 periods); compute
  // time has 0.1 us bins (up to 200 us).
  TelemetryReader(TelemetryRing& ring, double rate_hz, std::size_t keep_records = 0);
  // Takes everything in the ring now; returns how many records it took.
  std::size_t drain_nonrt();

  const DurationHistogram& periods() const noexcept { return periods_; }
  const DurationHistogram& compute() const noexcept { return compute_; }
  std::uint64_t records_read() const noexcept { return read_; }
  std::uint64_t overruns() const noexcept { return overruns_; }
  double max_force_N() const noexcept { return max_force_N_; }
  // Mean |F| of the records read so far (N); 0 before any.
  double mean_force_N() const noexcept { return read_ ? sum_force_N_ / static_cast<double>(read_) : 0; }
  const TelemetryRecord& last() const noexcept { return last_; }
  const std::vector<TelemetryRecord>& kept() const noexcept { return kept_; }
  // Measures the felt peak of `program`'s grating from the records drained from now on whose tick
  // starts at or after `from_s` (s since the loop started: the end of the start ramp, so that the
  // fade-in is not counted as the material); none without a grating. felt() is then the meter, else nullptr.
  // The meter is fed the texture terms' force at each record's position (texture_force.hpp), not
  // the force written: friction or a spring beside the grating is not its roughness.
  void measure_felt_peak(const schema::PatchProgram& program, double from_s) {
    felt_ = FeltPeakMeter::for_program(program);
    texture_ = TextureForce::for_program(program);
    felt_from_s_ = from_s;
  }
  const FeltPeakMeter* felt() const noexcept { return felt_ ? &*felt_ : nullptr; }
  // Largest |F| of the texture terms alone over the measured records (N); nullopt without a texture.
  std::optional<double> felt_texture_max_N() const noexcept {
    return texture_ ? std::optional<double>(texture_->max_N()) : std::nullopt;
  }

 private:
  TelemetryRing& ring_;
  DurationHistogram periods_;
  DurationHistogram compute_;
  std::size_t keep_;
  std::vector<TelemetryRecord> kept_;
  std::uint64_t read_ = 0, overruns_ = 0;
  double max_force_N_ = 0, sum_force_N_ = 0;
  TelemetryRecord last_{};
  std::optional<FeltPeakMeter> felt_;
  std::optional<TextureForce> texture_;
  double felt_from_s_ = 0;
};

}  // namespace sandpaper::runtime
