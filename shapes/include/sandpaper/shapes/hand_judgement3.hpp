#pragma once
// Whether a run on the simulated hand (DynamicHand3) stayed stable and paid for its hold, by the
// 2-D path's criteria (docs/RUNTIME.md, "Stability of the shipped materials") carried to 3-D and to
// laps of a looping path instead of seconds of a one-second scan. docs/SHAPES.md, "The 3-DOF
// device model".
#include <cstdint>

#include "sandpaper/shapes/dynamic_hand3.hpp"

namespace sandpaper::shapes {

struct HandJudgement3 {
  // The active share paid for: what the zero-order hold added to the contact's work and what the
  // texture gave back (EnergyBalance3::hold_work_J + texture_work_J, the texture's only when
  // positive) is no more than the hand's damper dissipated over the ticks in contact (Colgate &
  // Schenkel's b > K T / 2 with the hand's b_h as b, in energy form: the damping at the port while
  // the wall acts must absorb what the hold makes).
  double active_work_J = 0;
  double hand_dissipated_J = 0;             // over the whole run
  double hand_dissipated_in_contact_J = 0;  // over the intervals after a tick whose force was not zero
  bool active_paid = true;
  // No force reached the device's maximum (a growing oscillation runs into it; 2-D criterion 1).
  double peak_force_N = 0;
  double max_force_N = 0;
  bool below_clamp = true;
  // Bounded excursion (2-D criterion 2): the handle never strays from the hand's path by more than
  // the free hand does (same path, no renderer) + 1.5 x the largest force / k_h + 1 mm.
  double max_excursion_m = 0;
  double free_excursion_m = 0;
  double excursion_bound_m = 0;
  bool bounded = true;
  // No growth (2-D criterion 3, per lap): the largest hand-relative energy over the last whole lap
  // is at most 2 x that over the first + 10 uJ. Judged only with two whole laps or more.
  std::uint64_t laps = 0;
  double first_lap_energy_J = 0;
  double last_lap_energy_J = 0;
  bool growth_judged = false;
  bool no_growth = true;

  bool stable() const noexcept { return below_clamp && bounded && no_growth; }
};

// Judges `hand`'s recorded run (every tick recorded: capacity at least the run's ticks), whose
// largest written force was `peak_force_N` of a maximum `max_force_N`, and whose hold and texture
// did `active_work_J` (hold_work_J + max(0, texture_work_J)); `free_excursion_m` from
// free_hand_excursion_m.
HandJudgement3 judge_hand_run(const DynamicHand3& hand, double peak_force_N, double max_force_N, double active_work_J,
                              double free_excursion_m);

// The largest |handle - path point| of the free hand: `path` walked by `model`'s hand with no force,
// read at `rate_hz` for `seconds`, m.
double free_hand_excursion_m(const HandPath3& path, const runtime::HandModel& model, double rate_hz, double seconds);

}  // namespace sandpaper::shapes
