#pragma once
// What the servo loop plays: anything that turns the hand's state into a force each tick. A single
// patch (PatchEvaluator) and a workspace of patches (WorkspaceEvaluator) are both force sources.
#include <glm/vec2.hpp>

namespace sandpaper::runtime {

struct HandState {
  glm::dvec2 position_m{0, 0};       // relative to the workspace (or single patch) centre
  glm::dvec2 velocity_m_s{0, 0};     // filtered from positions
  glm::dvec2 acceleration_m_s2{0, 0};
};

class ForceSource {
 public:
  virtual ~ForceSource() = default;
  // The force (N) to send for `hand`; `dt_s` is the time since the previous tick (s), used to
  // advance state (masses, lags, energy tank). Servo thread only: no allocation, locks or I/O.
  virtual glm::dvec2 force_rt(const HandState& hand, double dt_s) noexcept = 0;
  // Returns every piece of state to its start: masses at rest under `hand`, lags caught up, clocks
  // at zero, energy tanks full. The loop calls it before the first tick.
  virtual void reset_rt(const HandState& hand) noexcept = 0;
};

}  // namespace sandpaper::runtime
