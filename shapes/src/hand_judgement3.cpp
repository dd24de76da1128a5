#include "sandpaper/shapes/hand_judgement3.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace sandpaper::shapes {
namespace {

// The 2-D path's margins (docs/RUNTIME.md, tests/e2e/dynamic_hand_stability_test.cpp): room for the
// hand's resonance (Q = 1.35) over the static deflection, and for a texture deflecting the handle
// differently on every lap.
constexpr double kDeflectionFactor = 1.5;
constexpr double kExcursionSlack_m = 1e-3;
constexpr double kGrowthFactor = 2.0;
constexpr double kGrowthSlack_J = 10e-6;

}  // namespace

HandJudgement3 judge_hand_run(const DynamicHand3& hand, double peak_force_N, double max_force_N, double active_work_J,
                              double free_excursion_m) {
  HandJudgement3 j;
  const auto& r = hand.records();
  j.active_work_J = active_work_J;
  j.hand_dissipated_J = hand.hand_dissipated_J();
  for (std::size_t k = 0; k + 1 < r.size(); ++k)
    if (r[k].force_N != glm::dvec3{0.0}) j.hand_dissipated_in_contact_J += r[k + 1].hand_dissipated_J - r[k].hand_dissipated_J;
  j.active_paid = active_work_J <= j.hand_dissipated_in_contact_J;
  j.peak_force_N = peak_force_N;
  j.max_force_N = max_force_N;
  j.below_clamp = peak_force_N < max_force_N;

  for (const auto& t : r) j.max_excursion_m = std::max(j.max_excursion_m, glm::length(t.handle_m - t.hand_m));
  j.free_excursion_m = free_excursion_m;
  j.excursion_bound_m = free_excursion_m + kDeflectionFactor * peak_force_N / hand.model().stiffness_N_per_m + kExcursionSlack_m;
  j.bounded = j.max_excursion_m <= j.excursion_bound_m;

  if (!r.empty()) {
    const double lap = hand.path().lap_s();
    const double t0 = r.front().t_s;
    j.laps = static_cast<std::uint64_t>(std::floor((r.back().t_s - t0) / lap));
    if (j.laps >= 2) {
      const double last_from = t0 + static_cast<double>(j.laps - 1) * lap, last_to = t0 + static_cast<double>(j.laps) * lap;
      for (const auto& t : r) {
        if (t.t_s < t0 + lap) j.first_lap_energy_J = std::max(j.first_lap_energy_J, t.energy_J);
        if (t.t_s >= last_from && t.t_s < last_to) j.last_lap_energy_J = std::max(j.last_lap_energy_J, t.energy_J);
      }
      j.growth_judged = true;
      j.no_growth = j.last_lap_energy_J <= kGrowthFactor * j.first_lap_energy_J + kGrowthSlack_J;
    }
  }
  return j;
}

double free_hand_excursion_m(const HandPath3& path, const runtime::HandModel& model, double rate_hz, double seconds) {
  DynamicHand3 free(DeviceLimits3{}, path, model, 0);
  const auto ticks = static_cast<long>(std::llround(seconds * rate_hz));
  double largest = 0;
  for (long k = 0; k < ticks; ++k) {
    const double t = static_cast<double>(k) / rate_hz;
    glm::dvec3 x{0.0};
    free.read_position_rt(t, x);
    largest = std::max(largest, glm::length(x - path.position(t)));
    free.write_force_rt(glm::dvec3{0.0});
  }
  return largest;
}

}  // namespace sandpaper::shapes
