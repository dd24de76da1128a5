// The experiment's presentation envelope (runtime/envelope_source.hpp): the force ramps up from
// zero, holds, ramps down to zero and stays there; it never steps; its ticks do not allocate.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <glm/geometric.hpp>

#include "allocation_counter.hpp"
#include "sandpaper/runtime/envelope_source.hpp"

namespace sandpaper::runtime {
namespace {

// A constant 2 N push along x, with a counter of resets, to see what the envelope does to it.
class Constant final : public ForceSource {
 public:
  explicit Constant(int* resets) : resets_(resets) {}
  glm::dvec2 force_rt(const HandState&, double) noexcept override { return {2.0, 0.0}; }
  void reset_rt(const HandState&) noexcept override { ++*resets_; }

 private:
  int* resets_;
};

TEST(EnvelopeSource, RampsHoldsAndEndsAtZero) {
  int resets = 0;
  EnvelopeSource e(std::make_unique<Constant>(&resets), 0.1, 0.5, 1.5);
  EXPECT_DOUBLE_EQ(e.length_s(), 0.7);
  EXPECT_DOUBLE_EQ(e.gain_at(0), 0);
  EXPECT_DOUBLE_EQ(e.gain_at(0.05), 0.75);
  EXPECT_DOUBLE_EQ(e.gain_at(0.3), 1.5);
  EXPECT_NEAR(e.gain_at(0.65), 0.75, 1e-12);
  EXPECT_DOUBLE_EQ(e.gain_at(0.7), 0);
  EXPECT_DOUBLE_EQ(e.gain_at(5), 0);

  e.reset_rt({});
  EXPECT_EQ(resets, 1);
  const double dt = 1e-3;
  double previous = 0, largest_step = 0, peak = 0;
  for (int i = 0; i < 1000; ++i) {
    const double f = glm::length(e.force_rt({}, dt));
    largest_step = std::max(largest_step, std::abs(f - previous));
    peak = std::max(peak, f);
    previous = f;
  }
  EXPECT_NEAR(peak, 3.0, 1e-9);                 // 2 N x gain 1.5
  EXPECT_LE(largest_step, 3.0 * dt / 0.1 + 1e-9);  // no step larger than one tick of the ramp
  EXPECT_EQ(previous, 0.0);                     // over after 0.7 s and silent since

  // reset starts the envelope again from zero.
  e.reset_rt({});
  EXPECT_EQ(glm::length(e.force_rt({}, dt)), 0.0);
  EXPECT_GT(glm::length(e.force_rt({}, dt)), 0.0);
}

TEST(EnvelopeSource, RefusesBadArguments) {
  int resets = 0;
  EXPECT_THROW(EnvelopeSource(nullptr, 0.1, 1), std::invalid_argument);
  EXPECT_THROW(EnvelopeSource(std::make_unique<Constant>(&resets), -0.1, 1), std::invalid_argument);
  EXPECT_THROW(EnvelopeSource(std::make_unique<Constant>(&resets), 0.1, NAN), std::invalid_argument);
  EXPECT_THROW(EnvelopeSource(std::make_unique<Constant>(&resets), 0.1, 1, -1), std::invalid_argument);
}

TEST(EnvelopeSource, TicksDoNotAllocate) {
  int resets = 0;
  EnvelopeSource e(std::make_unique<Constant>(&resets), 0.01, 0.02);
  e.reset_rt({});
  test::CountedAllocations counted;
  for (int i = 0; i < 100; ++i) (void)e.force_rt({}, 1e-3);
  EXPECT_EQ(counted.stop(), 0u);
}

}  // namespace
}  // namespace sandpaper::runtime
