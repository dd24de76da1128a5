#pragma once
// One stimulus presentation as a force source: the inner source's force times a gain that rises
// linearly from 0 over `ramp_s`, holds at `gain` for `hold_s`, falls back to 0 over `ramp_s`, then
// stays 0. Experiments hand one of these to the running loop per trial (docs/EXPERIMENTS.md), so the
// hand never feels a step between stimuli; the envelope keeps its own clock from reset_rt on.
#include <memory>

#include "sandpaper/runtime/force_source.hpp"

namespace sandpaper::runtime {

class EnvelopeSource final : public ForceSource {
 public:
  // `ramp_s` >= 0, `hold_s` >= 0, `gain` >= 0, all finite; throws std::invalid_argument otherwise or
  // for a null inner source.
  EnvelopeSource(std::unique_ptr<ForceSource> inner, double ramp_s, double hold_s, double gain = 1.0);

  glm::dvec2 force_rt(const HandState& hand, double dt_s) noexcept override;
  void reset_rt(const HandState& hand) noexcept override;

  // The gain at envelope time t (s since reset); pure, for tests and plots.
  double gain_at(double t_s) const noexcept;
  // ramp + hold + ramp: from reset until the force is zero for good, s.
  double length_s() const noexcept { return 2 * ramp_s_ + hold_s_; }

 private:
  std::unique_ptr<ForceSource> inner_;
  double ramp_s_, hold_s_, gain_;
  double t_s_ = 0;
};

}  // namespace sandpaper::runtime
