#pragma once
// A 3-D servo run: each tick reads a Device3, differentiates and filters its velocity, asks a scene
// renderer for the force, ramps it in, clamps its magnitude to the device's maximum and writes it,
// on a virtual clock (simulated time, as fast as it computes) or the steady clock (a device a
// person holds). It keeps the run's energy balance at the device's port. runtime's run_servo_loop
// (servo_loop.hpp) in 3-D, kept small: no telemetry, no timing statistics, no command quantum.
// docs/SHAPES.md, "The 3-DOF device model".
#include <concepts>
#include <cstdint>
#include <optional>
#include <type_traits>

#include <glm/vec3.hpp>

#include "sandpaper/runtime/servo_clock.hpp"
#include "sandpaper/shapes/device3.hpp"
#include "sandpaper/shapes/hand_judgement3.hpp"

namespace sandpaper::shapes {

// Anything with `glm::dvec3 update_rt(const glm::dvec3& device_m, const glm::dvec3& velocity_mps)`
// returning the force on the device (N), and optionally `void reset_rt(const glm::dvec3&)` (called
// once, with the first position) and `texture_force_rt()` (the lateral-force texture's share of the
// last force, N, kept apart in the energy balance): SceneRenderer, TexturedContact, ProxyRenderer,
// a test's renderer. Refers to it without owning it, and without std::function (no allocation).
class SceneForce {
 public:
  template <class R>
    requires(!std::same_as<std::remove_cvref_t<R>, SceneForce>) && requires(R& r, const glm::dvec3& x) {
      { r.update_rt(x, x) } -> std::convertible_to<glm::dvec3>;
    }
  SceneForce(R& renderer) noexcept  // NOLINT(google-explicit-constructor): any renderer passes as one
      : object_(&renderer), update_(&update_of<R>), reset_(&reset_of<R>), texture_(&texture_of<R>) {}
  glm::dvec3 update_rt(const glm::dvec3& device_m, const glm::dvec3& velocity_mps) noexcept {
    return update_(object_, device_m, velocity_mps);
  }
  void reset_rt(const glm::dvec3& device_m) noexcept { reset_(object_, device_m); }
  // The texture's share of the last update's force (N); zero for a renderer without a texture.
  glm::dvec3 texture_force_rt() const noexcept { return texture_(object_); }

 private:
  template <class R>
  static glm::dvec3 update_of(void* o, const glm::dvec3& x, const glm::dvec3& v) noexcept {
    return static_cast<R*>(o)->update_rt(x, v);
  }
  template <class R>
  static void reset_of(void* o, const glm::dvec3& x) noexcept {
    if constexpr (requires(R& r) { r.reset_rt(x); }) static_cast<R*>(o)->reset_rt(x);
  }
  template <class R>
  static glm::dvec3 texture_of(void* o) noexcept {
    if constexpr (requires(R& r) {
                    { r.texture_force_rt() } -> std::convertible_to<glm::dvec3>;
                  })
      return static_cast<R*>(o)->texture_force_rt();
    else
      return glm::dvec3{0.0};
  }
  void* object_;
  glm::dvec3 (*update_)(void*, const glm::dvec3&, const glm::dvec3&) noexcept;
  void (*reset_)(void*, const glm::dvec3&) noexcept;
  glm::dvec3 (*texture_)(void*) noexcept;
};

struct SceneServoConfig {
  double rate_hz = 1000.0;           // 900 Hz .. 10 kHz, and within the device's limits
  double duration_s = 10.0;          // ticks = round(duration * rate); > 0
  double velocity_cutoff_hz = 50.0;  // first-order low-pass on finite-difference velocity (as ServoConfig)
  double ramp_s = 0.05;              // the force is scaled by t / ramp_s over the first ramp_s (0: none)
  double velocity_limit_m_s = 2.0;   // filtered handle speed above this stops the run (VelocityLimit)
};

enum class SceneStop {
  Completed,          // "completed"
  DeviceReadFailed,   // "device_read_failed"
  PositionNotFinite,  // "position_not_finite"
  ForceNotFinite,     // "force_not_finite": the renderer returned NaN or infinity
  VelocityLimit,      // "velocity_limit": the handle ran away (faster than velocity_limit_m_s)
  DeviceWriteFailed,  // "device_write_failed"
};
// Stable snake_case names, as runtime::stop_cause_name's.
const char* scene_stop_name(SceneStop stop) noexcept;

// The energy at the device's port over a run (J). With F_k the force written at tick k (held until
// the next read: a zero-order hold) and x_k the position read at tick k, the force split into the
// contact's share C_k (the proxy's spring, damper and friction, and a surface's relief: a passive
// law) and the texture's T_k (texture_force_rt: the thesis' lateral-force texture, F = -k grad h at
// the proxy):
//
//   W = sum_k F_k . (x_{k+1} - x_k)                      the device force's work on the handle (exact
//                                                        for a held force)
//   E = sum_k 1/2 (C_k + C_{k+1}) . (x_{k+1} - x_k)      the contact law's own work along the path the
//                                                        handle took (the trapezoid: no hold)
//   Z = sum_k C_k . (x_{k+1} - x_k) - E                  what the hold adds to the contact's work
//   T = sum_k T_k . (x_{k+1} - x_k)                      the texture's work
//
// so that W = E + Z + T. Colgate & Schenkel ("Passivity of a class of sampled-data systems",
// J. Robotic Systems 14(1), 1997) split a sampled virtual wall the same way: a passive law (a
// spring K, a damper B) and the hold, which makes the spring act as if it had a negative damper of
// up to K T_s / 2, to be paid for by physical damping at the port (b > K T_s / 2 + |B|). Here:
//
// - No energy gained: the contact law is passive, so at every relaxed tick (force exactly zero: a
//   proxy out of contact, its spring storing nothing) E <= tolerance -- the law has given back no
//   more than the hand put in (a passivity observer, Hannaford & Ryu 2002, read at the ticks where
//   nothing is stored). energy_gained_J is the largest E at a relaxed tick (0 at the start);
//   tolerance_J bounds the trapezoid's error where the law has a kink (contact starting or ending
//   within a tick): 1/2 |C_{k+1} - C_k| |x_{k+1} - x_k| summed over those ticks, + 1 nJ.
// - The hold's surplus Z and the texture's work T are not the law's: a gradient field laid on a
//   surface gives back, each time contact is made and broken, the difference of its potential
//   between the two points (bounded, but not zero). On the simulated hand both must be paid for by
//   the hand's damper while in contact (the 2-D path's reading of Colgate & Schenkel, with the hand's
//   b_h as the port's damping, docs/RUNTIME.md) and the hand must stay stable: judge_hand_run.
struct EnergyBalance3 {
  double work_on_handle_J = 0;            // W at the end
  double environment_work_J = 0;          // E at the end (negative while the law stores or has dissipated energy)
  double relaxed_environment_work_J = 0;  // E at the last relaxed tick: what the law kept (dissipated)
  double hold_work_J = 0;                 // Z at the end
  double texture_work_J = 0;              // T at the end
  double energy_gained_J = 0;             // the largest E at a relaxed tick
  double tolerance_J = 1e-9;
  std::uint64_t relaxed_ticks = 0;
  bool no_energy_gained() const noexcept { return energy_gained_J <= tolerance_J; }
};

struct SceneServoSummary {
  std::uint64_t ticks = 0;
  double rate_hz = 0;
  double duration_s = 0;              // servo time of the last tick
  SceneStop stop = SceneStop::Completed;
  std::uint64_t ticks_in_contact = 0;  // ticks whose force was not zero
  std::uint64_t clamped_ticks = 0;     // forces above the device's maximum, written at the maximum
  std::uint64_t ramped_ticks = 0;
  std::uint64_t ticks_outside_workspace = 0;  // positions the device reported outside its workspace
  double peak_force_N = 0;             // the largest |F| written
  double max_speed_m_s = 0;            // the largest filtered handle speed
  EnergyBalance3 energy;
  // Filled by the one-call run_scene_servo when the device is a DynamicHand3 (sim3d).
  std::optional<HandJudgement3> hand;
  // The run completed, gained no energy, and (on a simulated hand) the hold and the texture were
  // paid for and the hand stayed stable: the check, "no energy gained, no instability".
  bool passed() const noexcept {
    return stop == SceneStop::Completed && energy.no_energy_gained() && (!hand || (hand->active_paid && hand->stable()));
  }
};

// Plays `renderer` on `device` for config.duration_s with `clock`; returns when done. Nothing is
// allocated once the first tick starts. Stops at the first SceneStop; in every case a zero force
// is written once after the last tick. Throws std::invalid_argument for a rate outside 900 Hz -
// 10 kHz or the device's limits, a duration that is not positive and finite or shorter than a tick,
// a non-positive velocity cutoff or limit, or a negative ramp; or when the clock is virtual and
// the device cannot follow it.
SceneServoSummary run_scene_servo(SceneForce renderer, Device3& device, const SceneServoConfig& config,
                                  runtime::ServoClock& clock);

// One call: `seconds` at `rate_hz` (other settings SceneServoConfig's defaults), on the virtual
// clock when the device follows it (sim3d), else on the steady clock. On a DynamicHand3 it also
// plays the free hand over the same path (no renderer) and fills `hand` (judge_hand_run).
SceneServoSummary run_scene_servo(SceneForce renderer, Device3& device, double rate_hz, double seconds);

}  // namespace sandpaper::shapes
