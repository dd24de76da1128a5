#include "sandpaper/runtime/envelope_source.hpp"

#include <cmath>
#include <stdexcept>

namespace sandpaper::runtime {

EnvelopeSource::EnvelopeSource(std::unique_ptr<ForceSource> inner, double ramp_s, double hold_s, double gain)
    : inner_(std::move(inner)), ramp_s_(ramp_s), hold_s_(hold_s), gain_(gain) {
  if (!inner_) throw std::invalid_argument("EnvelopeSource: no inner force source");
  if (!std::isfinite(ramp_s) || ramp_s < 0) throw std::invalid_argument("EnvelopeSource: ramp must be >= 0 s");
  if (!std::isfinite(hold_s) || hold_s < 0) throw std::invalid_argument("EnvelopeSource: hold must be >= 0 s");
  if (!std::isfinite(gain) || gain < 0) throw std::invalid_argument("EnvelopeSource: gain must be >= 0");
}

double EnvelopeSource::gain_at(double t) const noexcept {
  if (t < 0 || t >= length_s()) return 0;
  if (ramp_s_ > 0 && t < ramp_s_) return gain_ * t / ramp_s_;
  const double fall = ramp_s_ + hold_s_;
  if (ramp_s_ > 0 && t > fall) return gain_ * (length_s() - t) / ramp_s_;
  return gain_;
}

glm::dvec2 EnvelopeSource::force_rt(const HandState& hand, double dt_s) noexcept {
  // The inner source keeps running through the ramps so its state (masses, lags) stays continuous.
  const glm::dvec2 f = inner_->force_rt(hand, dt_s);
  const double g = gain_at(t_s_);
  t_s_ += dt_s;
  return f * g;
}

void EnvelopeSource::reset_rt(const HandState& hand) noexcept {
  inner_->reset_rt(hand);
  t_s_ = 0;
}

}  // namespace sandpaper::runtime
