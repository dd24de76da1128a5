#include "sandpaper/runtime/workspace_evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sandpaper::runtime {
namespace {

std::vector<PatchRect> rects_of(const schema::WorkspaceProgram& ws) {
  std::vector<PatchRect> rects;
  rects.reserve(ws.patches.size());
  for (std::size_t i = 0; i < ws.patches.size(); ++i) {
    const auto& p = ws.patches[i];
    const std::string what = "patch " + std::to_string(i) + " (" + p.source + ")";
    if (!(std::isfinite(p.size_m[0]) && p.size_m[0] > 0 && std::isfinite(p.size_m[1]) && p.size_m[1] > 0))
      throw std::invalid_argument(what + ": size must be positive and finite");
    if (!std::isfinite(p.centre_m[0]) || !std::isfinite(p.centre_m[1]))
      throw std::invalid_argument(what + ": centre must be finite");
    // The patch evaluator zeroes force outside program.size_m; the lookup uses the placed size.
    // They must agree, or part of a placed patch would be silent (or the grid would be wrong).
    if (!p.program) throw std::invalid_argument(what + ": no program");
    if (p.program->size_m[0] != p.size_m[0] || p.program->size_m[1] != p.size_m[1])
      throw std::invalid_argument(what + ": placed size differs from its program's size_m; place it with schema::place_patch");
    rects.push_back({{p.centre_m[0], p.centre_m[1]}, {0.5 * p.size_m[0], 0.5 * p.size_m[1]}});
  }
  return rects;
}

glm::dvec2 workspace_half(const schema::WorkspaceProgram& ws) {
  if (!(std::isfinite(ws.size_m[0]) && ws.size_m[0] > 0 && std::isfinite(ws.size_m[1]) && ws.size_m[1] > 0))
    throw std::invalid_argument("workspace size must be positive and finite");
  return {0.5 * ws.size_m[0], 0.5 * ws.size_m[1]};
}

}  // namespace

WorkspaceEvaluator::WorkspaceEvaluator(const schema::WorkspaceProgram& workspace, double crossfade_s)
    : workspace_(workspace), crossfade_s_(crossfade_s), grid_(rects_of(workspace), workspace_half(workspace)) {
  if (!std::isfinite(crossfade_s) || crossfade_s < 0)
    throw std::invalid_argument("crossfade time must be finite and >= 0 s");
  evaluators_.reserve(workspace_.patches.size());
  centres_m_.reserve(workspace_.patches.size());
  for (std::size_t i = 0; i < workspace_.patches.size(); ++i) {
    const auto& p = workspace_.patches[i];
    try {
      evaluators_.push_back(std::make_unique<PatchEvaluator>(*p.program));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("patch " + std::to_string(i) + " (" + p.source + "): " + e.what());
    }
    centres_m_.push_back({p.centre_m[0], p.centre_m[1]});
  }
}

HandState WorkspaceEvaluator::relative_to(const HandState& hand, std::uint32_t patch) const noexcept {
  HandState h = hand;
  h.position_m = hand.position_m - centres_m_[patch];
  return h;
}

void WorkspaceEvaluator::reset_rt(const HandState& hand) noexcept {
  current_ = grid_.frontmost_at(hand.position_m);
  if (current_ != kNoPatch) evaluators_[current_]->reset_rt(relative_to(hand, current_));
  last_force_N_ = fade_from_N_ = {0, 0};
  fade_elapsed_s_ = 0;
  fading_ = false;
}

glm::dvec2 WorkspaceEvaluator::force_rt(const HandState& hand, double dt_s) noexcept {
  const glm::dvec2 p = hand.position_m;
  // A position the device cannot have reported is a fault: NaN stops the loop (as PatchEvaluator).
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan};
  }
  const std::uint32_t under = grid_.frontmost_at(p);
  if (under != current_) {
    // The patch just left sends nothing outside its rectangle, so the fade starts from the force
    // last sent (which may itself be part of an earlier fade) and ends on the entered patch's.
    current_ = under;
    if (under != kNoPatch) evaluators_[under]->reset_rt(relative_to(hand, under));
    fade_from_N_ = last_force_N_;
    fade_elapsed_s_ = 0;
    fading_ = crossfade_s_ > 0;
  }
  glm::dvec2 force{0, 0};
  if (under != kNoPatch) force = evaluators_[under]->force_rt(relative_to(hand, under), dt_s);
  if (fading_) {
    fade_elapsed_s_ += std::max(0.0, dt_s);
    const double w = std::min(1.0, fade_elapsed_s_ / crossfade_s_);
    force = fade_from_N_ + w * (force - fade_from_N_);
    if (w >= 1) fading_ = false;
  }
  if (std::isfinite(force.x) && std::isfinite(force.y)) last_force_N_ = force;
  return force;
}

}  // namespace sandpaper::runtime
