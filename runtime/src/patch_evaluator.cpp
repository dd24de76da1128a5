#include "sandpaper/runtime/patch_evaluator.hpp"

#include <cmath>
#include <limits>
#include <variant>

#include "term_forces.hpp"
#include "force_tables.hpp"
#include "term_checks.hpp"

namespace sandpaper::runtime {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The usual visitor of lambdas: one per term kind, so a new kind fails to compile until it has a kernel.
template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};

}  // namespace

PatchEvaluator::PatchEvaluator(const schema::PatchProgram& program, TableSampling tables)
    : program_(program), tank_(program.energy_budget_J, program.energy_refill_W), tables_(tables) {
  check_program(program);
  const std::size_t n = program.terms.size();
  slot_of_.assign(n, kNoSlot);
  passive_.assign(n, 1);
  for (std::size_t i = 0; i < n; ++i) {
    const schema::Term& term = program.terms[i];
    passive_[i] = schema::is_passive(term) ? 1 : 0;
    if (!passive_[i]) any_active_ = true;
    if (!schema::has_state(term)) continue;
    slot_of_[i] = static_cast<std::uint32_t>(slots_.size());
    Slot slot;
    if (const auto* masses = std::get_if<schema::PointMassesTerm>(&term))
      slot.max_substep_s = max_point_mass_substep_s(*masses);
    slots_.push_back(slot);
  }
  reset_rt(HandState{});
}

std::uint32_t PatchEvaluator::substeps_for(const schema::PointMassesTerm& term, double dt_s) noexcept {
  return point_mass_substeps(max_point_mass_substep_s(term), dt_s);
}

const TermState* PatchEvaluator::state_of(std::size_t term_index) const noexcept {
  if (term_index >= slot_of_.size() || slot_of_[term_index] == kNoSlot) return nullptr;
  return &slots_[slot_of_[term_index]].state;
}

void PatchEvaluator::reset_rt(const HandState& hand) noexcept {
  for (std::size_t i = 0; i < slot_of_.size(); ++i) {
    if (slot_of_[i] == kNoSlot) continue;
    TermState& state = slots_[slot_of_[i]].state;
    state = TermState{};
    state.follower_m = hand.position_m;
    state.adhesion_m = hand.position_m;
    if (const auto* masses = std::get_if<schema::PointMassesTerm>(&program_.terms[i]))
      state.masses = point_masses_at_rest(*masses, hand.position_m);
  }
  tank_.fill();
}

void PatchEvaluator::advance_rt(const HandState& hand, double dt_s) noexcept {
  if (!(dt_s > 0) || !std::isfinite(dt_s)) return;
  for (std::size_t i = 0; i < slot_of_.size(); ++i) {
    if (slot_of_[i] == kNoSlot) continue;
    Slot& slot = slots_[slot_of_[i]];
    const schema::Term& term = program_.terms[i];
    if (const auto* masses = std::get_if<schema::PointMassesTerm>(&term)) {
      advance_point_masses(*masses, slot.max_substep_s, hand.position_m, hand.velocity_m_s, dt_s, slot.state.masses);
    } else if (const auto* follower = std::get_if<schema::FollowerSpringTerm>(&term)) {
      // Exact for a hand held still over the tick: the lag's step response, whatever dt / lag is.
      slot.state.follower_m += (1.0 - std::exp(-dt_s / follower->lag_s)) * (hand.position_m - slot.state.follower_m);
    } else if (const auto* friction = std::get_if<schema::FrictionTerm>(&term)) {
      laws::advance_friction(*friction, hand.position_m, hand.velocity_m_s, slot.state.adhesion_m, slot.state.sticking);
    } else if (const auto* nap = std::get_if<schema::NapFrictionTerm>(&term)) {
      laws::advance_nap_friction(*nap, hand.position_m, hand.velocity_m_s, slot.state.adhesion_m, slot.state.sticking);
    } else if (const auto* attractor = std::get_if<schema::AttractorTerm>(&term)) {
      // Wrapped to one period so that hours of play keep the phase's resolution.
      double t = slot.state.time_s + dt_s;
      if (t >= attractor->period_s) t -= attractor->period_s * std::floor(t / attractor->period_s);
      slot.state.time_s = t;
    }
  }
}

glm::dvec2 PatchEvaluator::force_rt(const HandState& hand, double dt_s) noexcept {
  const glm::dvec2 p = hand.position_m;
  // A position the device cannot have reported is a fault; NaN makes the loop stop on it rather
  // than play the zero force the patch-rectangle test would otherwise give.
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return {kNaN, kNaN};
  advance_rt(hand, dt_s);
  const bool inside = std::abs(p.x) <= 0.5 * program_.size_m[0] && std::abs(p.y) <= 0.5 * program_.size_m[1];

  glm::dvec2 passive{0, 0}, active{0, 0};
  if (inside) {
    const glm::dvec2 v = hand.velocity_m_s;
    for (std::size_t i = 0; i < program_.terms.size(); ++i) {
      const TermState* state = slot_of_[i] == kNoSlot ? nullptr : &slots_[slot_of_[i]].state;
      const glm::dvec2 f = std::visit(
          Overloaded{
              [&](const schema::SpringTerm& t) -> glm::dvec2 {
                return -t.stiffness_N_per_m * (p - glm::dvec2{t.centre_m[0], t.centre_m[1]});
              },
              [&](const schema::DamperTerm& t) -> glm::dvec2 { return -t.damping_Ns_per_m * v; },
              [&](const schema::GratingTerm& t) {
                return tables_ == TableSampling::Hold ? tables::grating_force_held(t, p) : tables::grating_force(t, p);
              },
              [&](const schema::HeightFieldTerm& t) {
                return tables_ == TableSampling::Hold ? tables::height_field_force_held(t, p) : tables::height_field_force(t, p);
              },
              [&](const schema::ConstantForceTerm& t) { return laws::constant_force(t); },
              [&](const schema::NapTerm& t) { return laws::nap(t, v); },
              [&](const schema::PeriodicTerm& t) { return laws::periodic(t, p); },
              [&](const schema::RidgeTerm& t) { return laws::ridge(t, p); },
              [&](const schema::BowlTerm& t) { return laws::bowl(t, p); },
              [&](const schema::LinearFieldTerm& t) { return laws::linear_field(t, p); },
              [&](const schema::LinearSpringTerm& t) { return laws::linear_spring(t, p); },
              [&](const schema::MinusTerm& t) { return laws::minus(t, v, hand.acceleration_m_s2); },
              [&](const schema::FollowerSpringTerm& t) { return laws::follower_spring(t, p, state->follower_m); },
              [&](const schema::PointMassesTerm& t) { return point_masses_hand_force(t, state->masses, p, v); },
              [&](const schema::AttractorTerm& t) { return laws::attractor(t, p, state->time_s); },
              [&](const schema::FrictionTerm& t) { return laws::friction(t, p, state->adhesion_m); },
              [&](const schema::NapFrictionTerm& t) -> glm::dvec2 { return -t.stiffness_N_per_m * (p - state->adhesion_m); },
          },
          program_.terms[i]);
      (passive_[i] ? passive : active) += f;
    }
  }
  if (!any_active_) return passive;
  // The tank meters the non-passive share even when it is zero, so that it refills between visits.
  const double power_W = active.x * hand.velocity_m_s.x + active.y * hand.velocity_m_s.y;
  return passive + tank_.pass_rt(power_W, dt_s) * active;
}

}  // namespace sandpaper::runtime
