#pragma once
// The simulated 3-DOF device, sim3d, with a hand that yields: runtime's DynamicHandJoystick in 3-D.
// The handle is a mass m_h; the hand is a spring k_h and a damper b_h pulling it toward the
// scripted path point p(t) (hand_path3.hpp); the commanded force F acts on it too:
//
//     m_h x'' = k_h (p(t) - x) + b_h (p'(t) - x') + F
//
// F is held from one tick's write to the next read (a zero-order hold, as a motor amplifier does),
// and the handle is integrated between reads by semi-implicit Euler in equal substeps of at most
// HandModel::max_substep_s, as in runtime/src/dynamic_hand.cpp. Same model, defaults and source
// (runtime::HandModel: van Beek et al. 2015, Fig. 3). docs/SHAPES.md, "The 3-DOF device model".
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "sandpaper/runtime/dynamic_hand.hpp"
#include "sandpaper/shapes/device3.hpp"
#include "sandpaper/shapes/hand_path3.hpp"

namespace sandpaper::shapes {

// One tick, as the energy and stability checks need it (scene_servo.hpp). SI units.
struct HandTick3 {
  double t_s = 0;
  glm::dvec3 hand_m{0.0};               // the scripted path point
  glm::dvec3 hand_velocity_m_s{0.0};
  glm::dvec3 handle_m{0.0};             // what the device reported
  glm::dvec3 handle_velocity_m_s{0.0};
  glm::dvec3 force_N{0.0};              // written this tick, held until the next read
  double energy_J = 0;                  // hand-relative: 1/2 m |v - p'|^2 + 1/2 k |x - p|^2
  double hand_dissipated_J = 0;         // by the hand's damper since the start: integral of b |p' - v|^2 dt
  double work_on_handle_J = 0;          // by the device's force since the start: sum of F . dx over the substeps
};

class DynamicHand3 final : public Device3 {
 public:
  // `capacity_ticks`: ticks recorded (reserved now; ticks beyond it are played, not recorded).
  // Throws std::invalid_argument for a non-positive or non-finite mass, a negative or non-finite
  // stiffness or damping, or a non-positive substep. The handle starts on the path, moving with it,
  // so the run starts with no hand-relative energy.
  DynamicHand3(DeviceLimits3 limits, HandPath3 path, runtime::HandModel model, std::size_t capacity_ticks);

  const DeviceLimits3& limits() const noexcept override { return limits_; }
  // Integrates the handle from the previous read to t_s (s) under the held force; reports where it is.
  bool read_position_rt(double t_s, glm::dvec3& position_m) noexcept override;
  // Holds `force_N` on the handle until the next read; records the tick (a write with no read
  // before it, such as a run's closing zero force, is obeyed and not recorded).
  bool write_force_rt(const glm::dvec3& force_N) noexcept override;

  const runtime::HandModel& model() const noexcept { return model_; }
  const HandPath3& path() const noexcept { return path_; }
  glm::dvec3 handle_position() const noexcept { return x_; }
  glm::dvec3 handle_velocity() const noexcept { return v_; }
  // Hand-relative energy at the last read (J).
  double energy_J() const noexcept;
  // Totals since the start (J): the hand's damper's dissipation, the device force's work on the handle.
  double hand_dissipated_J() const noexcept { return dissipated_J_; }
  double work_on_handle_J() const noexcept { return work_J_; }
  const std::vector<HandTick3>& records() const noexcept { return records_; }

 private:
  DeviceLimits3 limits_;
  HandPath3 path_;
  runtime::HandModel model_;
  std::size_t capacity_;
  std::vector<HandTick3> records_;
  bool started_ = false;
  bool read_since_write_ = false;
  double t_ = 0;
  glm::dvec3 x_{0.0}, v_{0.0};
  glm::dvec3 force_{0.0};  // held until the next read
  double dissipated_J_ = 0, work_J_ = 0;
};

// sim3d: a DynamicHand3 with the limits of calibration/devices/sim3d.toml (compiled in), walking
// `path` with `model`'s hand, recording up to `capacity_ticks` ticks. Throws as DynamicHand3 does.
DynamicHand3 open_sim3d(HandPath3 path, std::size_t capacity_ticks, runtime::HandModel model = {});

}  // namespace sandpaper::shapes
