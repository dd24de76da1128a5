#pragma once
// Evaluates a patch program at the hand's state: sums the terms' forces (N) and advances the state
// of the stateful ones (point masses, follower springs, attractors). Built off the servo thread from
// a PatchProgram; force_rt() neither allocates nor locks. docs/RUNTIME.md describes the terms'
// kernels, the point-mass integrator and the energy bound on non-passive terms.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "sandpaper/runtime/device.hpp"  // TableSampling
#include "sandpaper/runtime/energy_tank.hpp"
#include "sandpaper/runtime/force_source.hpp"
#include "sandpaper/runtime/point_masses.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::runtime {

// State one stateful term keeps between ticks, readable for display (the thesis animated its masses,
// 3.2.2) and tests. Only the fields of the term's own kind are used.
struct TermState {
  PointMassesState masses;          // PointMasses
  glm::dvec2 follower_m{0, 0};      // FollowerSpring: the lagging point m (m, patch coordinates)
  double time_s = 0;                // Attractor: time on the path, wrapped to [0, period)
  glm::dvec2 adhesion_m{0, 0};      // Friction: the adhesion point w (m, patch coordinates)
  bool sticking = true;             // Friction: stuck at w (else sliding)
};

class PatchEvaluator final : public ForceSource {
 public:
  // Keeps a reference: `program` must outlive the evaluator and not change while it is used.
  // Allocates one state slot per stateful term and starts as reset_rt() with the hand at the centre.
  // Throws std::invalid_argument if the program would make the tick index out of bounds, divide by
  // zero or integrate an unstable chain (the list is in src/term_checks.hpp: non-finite parameters,
  // periods, lags, radii or masses <= 0, point-mass count not 1 or 2, negative physical springs or
  // dampers, swirl <= -1, a negative energy budget or refill, patch size <= 0); table values
  // themselves are not checked.
  explicit PatchEvaluator(const schema::PatchProgram& program, TableSampling tables = TableSampling::Interpolate);
  // A temporary program would be gone before the first tick.
  explicit PatchEvaluator(schema::PatchProgram&&, TableSampling = TableSampling::Interpolate) = delete;

  // Advances every stateful term by dt_s (s; dt_s <= 0 advances nothing), then returns the sum of
  // every term's force at `hand`, the non-passive terms' share scaled by the energy tank. Zero
  // outside the patch rectangle (Appendix B: only the patch under the cursor sends force), though
  // state still advances there. Grating tables: linear interpolation with wrap-around; height
  // fields: bilinear interpolation of the gradient grid. A non-finite position gives a NaN force,
  // without advancing state, so that the servo loop stops on the device fault instead of playing zero.
  glm::dvec2 force_rt(const HandState& hand, double dt_s) noexcept override;
  // Masses at rest under gravity below the hand, follower points on the hand, attractor clocks at
  // zero, energy tank full.
  void reset_rt(const HandState& hand) noexcept override;

  // Substeps one tick of dt_s (s) needs for `term` (each h with h omega_max <= 0.25 and
  // h c/m <= 0.5), not capped: a material needing more than kMaxPointMassSubsteps at the device's
  // slowest servo period is one the runtime would slow down (point_masses.hpp). 0 for dt_s <= 0.
  static std::uint32_t substeps_for(const schema::PointMassesTerm& term, double dt_s) noexcept;

  // State of term `term_index` (its index in program.terms), or nullptr for a stateless term or an
  // index out of range. Not synchronised: read it on the servo thread or while the loop is stopped.
  const TermState* state_of(std::size_t term_index) const noexcept;
  // Energy (J) left in the tank that bounds the non-passive terms (docs/RUNTIME.md, "Energy bound").
  double energy_tank_J() const noexcept { return tank_.level_J(); }

 private:
  static constexpr std::uint32_t kNoSlot = UINT32_MAX;
  struct Slot {
    TermState state;
    double max_substep_s = 0;  // point masses: precomputed from their stiffness, damping and masses
  };

  void advance_rt(const HandState& hand, double dt_s) noexcept;

  const schema::PatchProgram& program_;
  std::vector<std::uint32_t> slot_of_;  // per term: index into slots_, or kNoSlot
  std::vector<std::uint8_t> passive_;   // per term: schema::is_passive
  std::vector<Slot> slots_;             // one per stateful term
  bool any_active_ = false;             // any non-passive term: only then is the tank metered
  EnergyTank tank_;
  TableSampling tables_ = TableSampling::Interpolate;
};

}  // namespace sandpaper::runtime
