#include "sandpaper/runtime/tick_timing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sandpaper::runtime {
namespace {
constexpr std::size_t kBins = static_cast<std::size_t>(TickTimingStats::kBinsPerPeriod * TickTimingStats::kPeriodsCovered);
}  // namespace

TickTimingStats::TickTimingStats(double period_ns) : bin_ns_(period_ns / static_cast<double>(kBinsPerPeriod)) {
  if (!(period_ns > 0) || !std::isfinite(period_ns)) throw std::invalid_argument("tick timing needs a positive period");
  bins_ = std::make_unique<std::uint32_t[]>(kBins);  // value-initialised: zeroed, and touched now rather than in a tick
}

void TickTimingStats::add_rt(std::int64_t ns) noexcept {
  const double bin = std::floor(static_cast<double>(std::max<std::int64_t>(ns, 0)) / bin_ns_);
  const auto index = bin >= static_cast<double>(kBins) ? kBins - 1 : static_cast<std::size_t>(bin);
  if (bins_[index] != UINT32_MAX) ++bins_[index];
  if (count_ == 0 || ns < min_ns_) min_ns_ = ns;
  if (count_ == 0 || ns > max_ns_) max_ns_ = ns;
  ++count_;
  const double delta = static_cast<double>(ns) - mean_ns_;
  mean_ns_ += delta / static_cast<double>(count_);
  m2_ns2_ += delta * (static_cast<double>(ns) - mean_ns_);
}

double TickTimingStats::min_us() const noexcept { return static_cast<double>(min_ns_) * 1e-3; }
double TickTimingStats::max_us() const noexcept { return static_cast<double>(max_ns_) * 1e-3; }
double TickTimingStats::mean_us() const noexcept { return mean_ns_ * 1e-3; }
double TickTimingStats::stddev_us() const noexcept {
  return count_ == 0 ? 0 : std::sqrt(m2_ns2_ / static_cast<double>(count_)) * 1e-3;
}

double TickTimingStats::percentile_us(double fraction) const noexcept {
  if (count_ == 0) return 0;
  const auto rank = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(fraction * static_cast<double>(count_))));
  std::uint64_t seen = 0;
  std::size_t i = 0;
  for (; i < kBins; ++i) {
    seen += bins_[i];
    if (seen >= rank) break;
  }
  const double middle_ns = (static_cast<double>(std::min(i, kBins - 1)) + 0.5) * bin_ns_;
  return std::clamp(middle_ns, static_cast<double>(min_ns_), static_cast<double>(max_ns_)) * 1e-3;
}

}  // namespace sandpaper::runtime
