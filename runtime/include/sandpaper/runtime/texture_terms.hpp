#pragma once
// A program's texture terms (gratings and height fields) summed directly, for a servo thread that
// needs only them: a material's texture laid on a surface in 3-D (shapes' SurfaceTexture). The
// same tables, interpolation and order as PatchEvaluator, so the same force to the bit, without
// its per-tick work for what a texture has none of: state, the patch's rectangle, the energy tank.
#include <vector>

#include <glm/vec2.hpp>

#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::runtime {

class TextureTerms {
 public:
  // `texture` holds gratings and height fields only (texture_terms_of) and must outlive this; its
  // tables are checked as PatchEvaluator checks them. Throws std::invalid_argument for any other
  // term, or a table PatchEvaluator would refuse.
  explicit TextureTerms(const schema::PatchProgram& texture);
  explicit TextureTerms(schema::PatchProgram&&) = delete;  // gone before the first tick

  // The terms' summed force (N) with the hand at p (m, patch coordinates); NaN for a non-finite p,
  // as PatchEvaluator gives. Real time: no allocation, lock, I/O or exception.
  glm::dvec2 force_rt(glm::dvec2 p) const noexcept;

 private:
  struct Term {
    const schema::GratingTerm* grating = nullptr;  // one of the two
    const schema::HeightFieldTerm* field = nullptr;
    glm::dvec2 direction{0.0};  // a grating's unit normal (cos, sin of its orientation), taken once
  };
  std::vector<Term> terms_;
};

}  // namespace sandpaper::runtime
