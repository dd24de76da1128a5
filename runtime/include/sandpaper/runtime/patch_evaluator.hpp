#pragma once
// Evaluates a patch program at the hand's state: sums the terms' forces (N). Built off the servo
// thread from a PatchProgram; force_rt() neither allocates nor locks.
#include <glm/vec2.hpp>

#include "sandpaper/runtime/force_source.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::runtime {

class PatchEvaluator final : public ForceSource {
 public:
  // Keeps a reference: `program` must outlive the evaluator and not change while it is used.
  // Throws std::invalid_argument if the program's shape would make the tick index out of bounds
  // (grating period <= 0 or table < 2 samples, height field tables not nx * ny, spacing <= 0,
  // patch size <= 0); table values themselves are not checked.
  explicit PatchEvaluator(const schema::PatchProgram& program);
  // A temporary program would be gone before the first tick.
  explicit PatchEvaluator(schema::PatchProgram&&) = delete;
  // Sum of every term's force at `hand`; zero outside the patch rectangle (Appendix B: only the
  // patch under the cursor sends force). Grating tables: linear interpolation with wrap-around;
  // height fields: bilinear interpolation of the gradient grid. A non-finite position gives a NaN
  // force so that the servo loop stops on the device fault instead of playing zero.
  glm::dvec2 force_rt(const HandState& hand, double dt_s) noexcept override;
  void reset_rt(const HandState& hand) noexcept override;

 private:
  const schema::PatchProgram& program_;
};

}  // namespace sandpaper::runtime
