#pragma once
// Plays a workspace of patches (thesis Appendix B): each tick the frontmost patch under the hand
// sends its force, evaluated at the hand's position relative to that patch's centre (velocity and
// acceleration unchanged). Built off the servo thread; force_rt() neither allocates nor locks.
#include <cstdint>
#include <memory>
#include <vector>

#include "sandpaper/runtime/force_source.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/patch_grid.hpp"
#include "sandpaper/schema/workspace_program.hpp"

namespace sandpaper::runtime {

class WorkspaceEvaluator final : public ForceSource {
 public:
  static constexpr std::uint32_t kNoPatch = PatchGrid::kNoPatch;
  static constexpr double kDefaultCrossfade_s = 0.002;

  // Keeps a reference: `workspace` must outlive the evaluator and not change while it is used.
  // `crossfade_s` (s, >= 0; 0 switches at once): when the frontmost patch under the hand changes
  // (to or from none included), the force goes linearly from what was last sent to the new patch's
  // force over this time, so a boundary never steps by more than the patches' own forces.
  // Throws std::invalid_argument for a placed size that differs from its program's size_m (use
  // schema::place_patch), a patch size <= 0, a negative or non-finite crossfade, or anything
  // PatchEvaluator refuses (the message names the patch).
  explicit WorkspaceEvaluator(const schema::WorkspaceProgram& workspace, double crossfade_s = kDefaultCrossfade_s);
  explicit WorkspaceEvaluator(schema::WorkspaceProgram&&, double = kDefaultCrossfade_s) = delete;

  glm::dvec2 force_rt(const HandState& hand, double dt_s) noexcept override;
  // Resets the patch under `hand` and ends any crossfade; other patches are reset on entry.
  void reset_rt(const HandState& hand) noexcept override;

  // Frontmost patch containing `p_m` (workspace coordinates), or kNoPatch. Pure, no allocation.
  std::uint32_t patch_at(glm::dvec2 p_m) const noexcept { return grid_.frontmost_at(p_m); }
  // The patch the last tick played (kNoPatch before the first tick or over no patch).
  std::uint32_t current_patch() const noexcept { return current_; }
  std::size_t patch_count() const noexcept { return evaluators_.size(); }
  const PatchGrid& grid() const noexcept { return grid_; }

 private:
  HandState relative_to(const HandState& hand, std::uint32_t patch) const noexcept;

  const schema::WorkspaceProgram& workspace_;
  double crossfade_s_;
  PatchGrid grid_;
  // unique_ptr: a PatchEvaluator refers to its program and may hold state; it never moves.
  std::vector<std::unique_ptr<PatchEvaluator>> evaluators_;
  std::vector<glm::dvec2> centres_m_;
  std::uint32_t current_ = kNoPatch;
  glm::dvec2 last_force_N_{0, 0};   // what the previous tick sent
  glm::dvec2 fade_from_N_{0, 0};    // force sent when the current crossfade began
  double fade_elapsed_s_ = 0;
  bool fading_ = false;
};

}  // namespace sandpaper::runtime
