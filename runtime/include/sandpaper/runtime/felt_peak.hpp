#pragma once
// The felt peak of a run: the mean over the grating ridges the hand crossed of each crossing's
// largest |F|, measured from the ticks as they were played. It is the quantity explain predicts as
// "felt at speed" (compiler/felt_at_speed.hpp), so a run and its prediction can be compared.
// Off the servo thread: fed from telemetry records after the ticks ran.
#include <cstddef>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>

#include "sandpaper/schema/grating_ridges.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::runtime {

class FeltPeakMeter {
 public:
  // For the first grating term of `program`; nullopt when it has none (height fields and force laws
  // have no ridges to count).
  static std::optional<FeltPeakMeter> for_program(const schema::PatchProgram& program);

  // One tick, in order: the hand's position (m) and the force written (N). A crossing enters a
  // ridge's span on one side and leaves it on the other; its value is the largest force along the
  // grating normal with the ridge's sign among its ticks (0 if none reads that sign). A ridge the
  // hand passes between two ticks is a crossing of 0, as in explain. Visits that turn back, and
  // the crossings under way when the run starts or ends, are not counted.
  void add_nonrt(glm::dvec2 position_m, glm::dvec2 force_N);

  // Ticks were lost (a telemetry ring that overflowed): the crossings under way are not counted,
  // and nothing is inferred about the gap.
  void break_nonrt();

  std::size_t crossings() const noexcept { return crossings_; }
  // Mean of the counted crossings' peaks, N; nullopt before any crossing.
  std::optional<double> felt_peak_N() const noexcept;

 private:
  struct Open {
    std::size_t ridge = 0;
    long long period = 0;
    double peak = 0;
    int entered_moving = 0;  // +1 / -1: the hand's direction along the normal when it entered; 0: unknown
  };
  FeltPeakMeter(const schema::GratingTerm& grating);
  void close(const Open& o, double x);

  glm::dvec2 normal_;
  double period_m_ = 0, size_ = 0;
  std::vector<schema::GratingRidge> ridges_;
  std::vector<Open> open_, next_;
  std::optional<double> last_x_;
  std::size_t crossings_ = 0;
  double sum_N_ = 0;
};

}  // namespace sandpaper::runtime
