#pragma once
// The simulated joystick with a hand that yields: the handle is a mass m_h, the hand a spring k_h and
// a damper b_h pulling it toward the scripted path point, so the commanded force moves the handle as
// on a real joystick. Between two reads the handle is integrated under hand spring + hand damper +
// the last commanded force, held constant over the tick (a zero-order hold, as a real motor
// amplifier does). docs/RUNTIME.md, "The dynamic hand", gives the model, the defaults and their source.
#include <cstddef>
#include <vector>

#include "sandpaper/runtime/sim_joystick.hpp"

namespace sandpaper::runtime {

// Mass-spring-damper hand, SI units. Defaults: the fit van Beek, Bergmann Tiest, Mugge and Kappers
// give as their typical example of postural arm dynamics measured at a grasped haptic-device handle
// (Sci. Rep. 5:18004, 2015, Fig. 3: M = 0.554 kg, B = 6.45 N*s/m, K = 135 N/m; one participant, one
// trial, one direction -- a plausible relaxed grasp, not a population mean).
struct HandModel {
  double mass_kg = 0.554;           // handle plus the hand and arm moving with it
  double stiffness_N_per_m = 135;   // pulls the handle toward the scripted path point
  double damping_Ns_per_m = 6.45;   // on the handle's velocity relative to the path's
  double max_substep_s = 1e-4;      // integration step bound (designed: omega h < 0.002 at the defaults)
};

// The hand's own state at one tick, for stability checks (docs/RUNTIME.md).
struct HandTickRecord {
  double t_s;
  glm::dvec2 hand_m;            // scripted path point
  glm::dvec2 hand_velocity_m_s;
  glm::dvec2 handle_m;          // what the device reported
  glm::dvec2 handle_velocity_m_s;
  double energy_J;              // 1/2 m |v - v_hand|^2 + 1/2 k |x - hand|^2
};

class DynamicHandJoystick final : public RecordingDevice {
 public:
  // Throws std::invalid_argument for a non-positive or non-finite mass, negative or non-finite
  // stiffness or damping, or a non-positive substep. The handle starts on the path moving with it.
  DynamicHandJoystick(DeviceLimits limits, HandScript script, HandModel model, std::size_t capacity_ticks);
  const DeviceLimits& limits() const noexcept override { return limits_; }
  // Integrates the handle from the previous read to t_s (s) and reports where it is.
  bool read_position_rt(double t_s, glm::dvec2& position_m) noexcept override;
  // Holds `force_N` on the handle until the next read; records the tick.
  bool write_force_rt(glm::dvec2 force_N) noexcept override;

  const HandModel& model() const noexcept { return model_; }
  const HandScript& script() const noexcept { return script_; }
  glm::dvec2 handle_position() const noexcept { return x_; }
  glm::dvec2 handle_velocity() const noexcept { return v_; }
  // Energy of the handle relative to the hand (J): kinetic in the path's frame plus hand-spring potential.
  double energy_J(double t_s) const noexcept;
  const std::vector<HandTickRecord>& hand_records() const noexcept { return hand_records_; }

 private:
  glm::dvec2 path_velocity(double t_s) const noexcept;

  DeviceLimits limits_;
  HandScript script_;
  HandModel model_;
  std::size_t capacity_;
  std::vector<HandTickRecord> hand_records_;
  bool started_ = false;
  double t_ = 0;
  glm::dvec2 x_{0, 0}, v_{0, 0};
  glm::dvec2 force_{0, 0};  // held until the next read
};

}  // namespace sandpaper::runtime
