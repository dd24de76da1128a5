#pragma once
// Statistics of the servo loop's tick durations (periods between tick starts, compute time per
// tick) in storage fixed by the servo period, never by the run's length: a run "until stopped"
// costs what a one-second run costs. Allocated before the first tick; add_rt never allocates.
#include <cstdint>
#include <memory>

namespace sandpaper::runtime {

class TickTimingStats {
 public:
  // Bins of period/1000 (0.1 us at 10 kHz, 1 us at 1 kHz) over 10 periods: 10,000 counters,
  // 40 KB. Longer values are counted in the last bin; min, max, mean and deviation stay exact.
  static constexpr std::int64_t kBinsPerPeriod = 1000;
  static constexpr std::int64_t kPeriodsCovered = 10;
  // `period_ns`: the servo period (> 0). Throws std::invalid_argument otherwise.
  explicit TickTimingStats(double period_ns);

  void add_rt(std::int64_t ns) noexcept;
  std::uint64_t count() const noexcept { return count_; }
  double min_us() const noexcept;
  double max_us() const noexcept;
  double mean_us() const noexcept;
  double stddev_us() const noexcept;
  // Nearest-rank percentile (fraction in 0..1): the middle of the bin holding that rank, held
  // within [min, max], so a run of identical durations reports that duration exactly. 0 when empty.
  double percentile_us(double fraction) const noexcept;

 private:
  double bin_ns_;
  std::unique_ptr<std::uint32_t[]> bins_;
  std::uint64_t count_ = 0;
  std::int64_t min_ns_ = 0, max_ns_ = 0;
  double mean_ns_ = 0, m2_ns2_ = 0;  // Welford's running mean and sum of squared deviations
};

}  // namespace sandpaper::runtime
