#pragma once
// The texture's share of what a run played: the force of a program's texture terms alone (its
// gratings and height fields, whose maximum lateral force the roughness map is about), evaluated
// at the positions the hand actually passed. Friction, springs and dampers beside a texture add to
// the force written to the device but not to its roughness (Minsky 1995, 5.3: roughness scaled on
// the lateral force of gratings), so a run predicts roughness from this share only. Off the servo
// thread: fed from telemetry records after the ticks ran.
#include <memory>
#include <optional>

#include <glm/vec2.hpp>

#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::runtime {

// `program` with its texture terms alone (gratings and height fields, in their order), the rest of
// it (patch size, limits) kept; its terms are empty when it has none.
schema::PatchProgram texture_terms_of(const schema::PatchProgram& program);

class TextureForce {
 public:
  // For the texture terms of `program` (grating, height field); nullopt when it has none.
  static std::optional<TextureForce> for_program(const schema::PatchProgram& program);

  // The texture terms' force (N) with the hand at `position_m` (m, from the patch centre). They
  // are stateless: the force depends on the position only.
  glm::dvec2 at_nonrt(glm::dvec2 position_m);
  // Largest |F| of the positions given so far (N).
  double max_N() const noexcept { return max_N_; }

 private:
  explicit TextureForce(std::unique_ptr<schema::PatchProgram> texture);
  std::unique_ptr<schema::PatchProgram> texture_;  // owned, so the evaluator's reference outlives moves
  std::unique_ptr<PatchEvaluator> evaluator_;
  double max_N_ = 0;
};

}  // namespace sandpaper::runtime
