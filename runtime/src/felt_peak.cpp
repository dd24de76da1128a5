#include "sandpaper/runtime/felt_peak.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

namespace sandpaper::runtime {

std::optional<FeltPeakMeter> FeltPeakMeter::for_program(const schema::PatchProgram& program) {
  for (const auto& t : program.terms)
    if (const auto* g = std::get_if<schema::GratingTerm>(&t); g && g->period_m > 0 && g->force_N.size() >= 2)
      return FeltPeakMeter(*g);
  return std::nullopt;
}

FeltPeakMeter::FeltPeakMeter(const schema::GratingTerm& grating)
    : normal_{std::cos(grating.orientation_rad), std::sin(grating.orientation_rad)},
      period_m_(grating.period_m),
      size_(static_cast<double>(grating.force_N.size())),
      ridges_(schema::grating_ridges(grating.force_N)) {}

void FeltPeakMeter::close(const Open& o, double x) {
  const auto& r = ridges_[o.ridge];
  const double shift = static_cast<double>(o.period) * size_;
  const bool crossed = (o.entered_moving > 0 && x >= r.last + 1 + shift) || (o.entered_moving < 0 && x <= r.first - 1 + shift);
  if (!crossed) return;
  ++crossings_;
  sum_N_ += o.peak;
}

void FeltPeakMeter::add_nonrt(glm::dvec2 position_m, glm::dvec2 force_N) {
  // The hand's place in table samples, unwrapped: period k's copy of a ridge lies k * size further on.
  const double x = (position_m.x * normal_.x + position_m.y * normal_.y) / period_m_ * size_;
  const double along = force_N.x * normal_.x + force_N.y * normal_.y;
  if (!std::isfinite(x) || !std::isfinite(along)) return;
  // A jump over more than kMaxPeriodsPerTick periods is no hand's motion (a replayed or faulty
  // position): a gap, not thousands of ridges stepped over; and far from the origin the doubles
  // that count periods stop being whole numbers.
  constexpr double kMaxPeriodsPerTick = 1000, kMaxPeriods = 1e12;
  if (std::abs(x) > kMaxPeriods * size_ || (last_x_ && std::abs(x - *last_x_) > kMaxPeriodsPerTick * size_)) {
    break_nonrt();
    return;
  }
  const int moving = !last_x_ ? 0 : x > *last_x_ ? 1 : x < *last_x_ ? -1 : 0;

  // Ridges passed between the last tick and this one with no tick on them: crossings of 0.
  if (last_x_ && moving != 0) {
    const double a = std::min(*last_x_, x), b = std::max(*last_x_, x);
    for (const auto& r : ridges_) {
      const double lo = r.first - 1, hi = r.last + 1;
      for (double k = std::ceil((a - lo) / size_); hi + k * size_ <= b; ++k) ++crossings_;
    }
  }

  next_.clear();
  for (std::size_t i = 0; i < ridges_.size(); ++i) {
    const auto& r = ridges_[i];
    const double lo = r.first - 1, hi = r.last + 1;
    const double k0 = std::floor((x - lo) / size_);
    for (double k : {k0, k0 - 1}) {
      if (!(lo + k * size_ < x && x < hi + k * size_)) continue;
      const auto period = static_cast<long long>(k);
      const double value = std::max(0.0, r.sign * along);
      auto it = std::find_if(open_.begin(), open_.end(), [&](const Open& o) { return o.ridge == i && o.period == period; });
      if (it != open_.end()) {
        it->peak = std::max(it->peak, value);
        next_.push_back(*it);
      } else {
        next_.push_back({i, period, value, moving});
      }
    }
  }
  for (const auto& o : open_)
    if (std::none_of(next_.begin(), next_.end(), [&](const Open& n) { return n.ridge == o.ridge && n.period == o.period; }))
      close(o, x);
  open_.swap(next_);
  last_x_ = x;
}

void FeltPeakMeter::break_nonrt() {
  open_.clear();
  last_x_.reset();
}

std::optional<double> FeltPeakMeter::felt_peak_N() const noexcept {
  if (crossings_ == 0) return std::nullopt;
  return sum_N_ / static_cast<double>(crossings_);
}

}  // namespace sandpaper::runtime
