#pragma once
// A force source that owns the program it plays, for hot swaps (swappable_source.hpp): the program
// must live until the application thread frees the retired source, so the source holds it. Optionally
// it raises a flag when the servo thread takes it over (SwappableSource resets a source under the
// hand when it picks it up), so the application knows what is playing now, not just what it offered.
#include <atomic>
#include <memory>
#include <utility>

#include "sandpaper/runtime/force_source.hpp"

namespace sandpaper::runtime {

// Program: schema::PatchProgram or schema::WorkspaceProgram; Evaluator: PatchEvaluator or
// WorkspaceEvaluator (constructed from a const Program& and `evaluator_args`, such as a device's
// TableSampling; throws what it throws for a bad program).
template <class Program, class Evaluator>
class OwningSource final : public ForceSource {
 public:
  template <class... EvaluatorArgs>
  explicit OwningSource(std::shared_ptr<const Program> program, std::shared_ptr<std::atomic<bool>> picked_up = nullptr,
                        EvaluatorArgs&&... evaluator_args)
      : program_(std::move(program)),
        evaluator_(*program_, std::forward<EvaluatorArgs>(evaluator_args)...),
        picked_up_(std::move(picked_up)) {}
  glm::dvec2 force_rt(const HandState& hand, double dt_s) noexcept override { return evaluator_.force_rt(hand, dt_s); }
  void reset_rt(const HandState& hand) noexcept override {
    evaluator_.reset_rt(hand);
    if (picked_up_) picked_up_->store(true, std::memory_order_release);
  }

 private:
  std::shared_ptr<const Program> program_;
  Evaluator evaluator_;
  std::shared_ptr<std::atomic<bool>> picked_up_;
};

}  // namespace sandpaper::runtime
