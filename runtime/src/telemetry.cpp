#include "sandpaper/runtime/telemetry.hpp"

#include <algorithm>
#include <cmath>

namespace sandpaper::runtime {

void DurationHistogram::add(double seconds) noexcept {
  const double us = seconds * 1e6;
  if (!std::isfinite(us) || us < 0) return;
  const auto bin = static_cast<std::size_t>(us / bin_us_);
  ++bins_[std::min(bin, kBins - 1)];
  ++count_;
  sum_us_ += us;
  max_us_ = std::max(max_us_, us);
}

double DurationHistogram::percentile_us(double fraction) const noexcept {
  if (count_ == 0) return 0;
  const auto rank = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(fraction * static_cast<double>(count_))));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < kBins; ++i) {
    seen += bins_[i];
    // The last bin is open-ended: its honest upper edge is the largest value seen.
    if (seen >= rank) return i + 1 == kBins ? max_us_ : std::min(max_us_, static_cast<double>(i + 1) * bin_us_);
  }
  return max_us_;
}

void DurationHistogram::clear() noexcept {
  bins_.fill(0);
  count_ = 0;
  sum_us_ = max_us_ = 0;
}

TelemetryReader::TelemetryReader(TelemetryRing& ring, double rate_hz, std::size_t keep_records)
    : ring_(ring), periods_(1e6 / rate_hz / 100.0), compute_(0.1), keep_(keep_records) {
  kept_.reserve(keep_records);
}

std::size_t TelemetryReader::drain_nonrt() {
  std::size_t taken = 0;
  TelemetryRecord r;
  while (ring_.pop_nonrt(r)) {
    ++taken;
    ++read_;
    if (r.tick > 0) periods_.add(r.period_s);
    compute_.add(r.compute_s);
    if (r.overrun) ++overruns_;
    const double magnitude = std::hypot(r.force_N.x, r.force_N.y);
    max_force_N_ = std::max(max_force_N_, magnitude);
    sum_force_N_ += magnitude;
    if (kept_.size() < keep_) kept_.push_back(r);
    if (r.t_s >= felt_from_s_) {
      const glm::dvec2 texture_N = texture_ ? texture_->at_nonrt(r.position_m) : r.force_N;
      if (felt_) {
        if (read_ > 1 && r.tick != last_.tick + 1) felt_->break_nonrt();
        felt_->add_nonrt(r.position_m, texture_N);
      }
    }
    last_ = r;
  }
  return taken;
}

}  // namespace sandpaper::runtime
