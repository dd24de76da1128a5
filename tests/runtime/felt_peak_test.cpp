// runtime::FeltPeakMeter: ridge crossings counted from ticks as a hand meets them. The expected
// values are worked by hand from an 8-sample table (below), not from the meter's own code.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "sandpaper/runtime/felt_peak.hpp"

using namespace sandpaper;

namespace {

// One period of 1 mm in 8 samples: a positive ridge on samples 1-3 (peak 2 N) and a negative ridge
// on samples 5-7 (peak 3 N); samples 0 and 4 are zero. Ridge spans, in samples: (0, 4) and (4, 8).
schema::PatchProgram program() {
  schema::GratingTerm g;
  g.period_m = 1e-3;
  g.force_N = {0, 1, 2, 1, 0, -1, -3, -1};
  schema::PatchProgram p;
  p.terms.emplace_back(g);
  return p;
}

// The runtime's linear read of the table at sample coordinate x (periodic).
double force_at(double x) {
  const std::vector<double> t{0, 1, 2, 1, 0, -1, -3, -1};
  const double u = x - 8 * std::floor(x / 8);
  const auto i = static_cast<std::size_t>(std::floor(u)) % 8;
  const double f = u - std::floor(u);
  return t[i] + f * (t[(i + 1) % 8] - t[i]);
}

// Feeds the meter a tick at sample coordinate x (the hand on the x axis, the grating's normal).
void tick(runtime::FeltPeakMeter& m, double x) { m.add_nonrt({x * 1e-3 / 8, 0}, {force_at(x), 0}); }

}  // namespace

TEST(FeltPeakMeter, NoGratingNoMeter) {
  schema::PatchProgram p;
  p.terms.emplace_back(schema::SpringTerm{});
  EXPECT_FALSE(runtime::FeltPeakMeter::for_program(p).has_value());
}

TEST(FeltPeakMeter, SlowCrossingsReadEachRidgesTablePeak) {
  auto m = *runtime::FeltPeakMeter::for_program(program());
  // 0.01 samples a tick from x = 0.5 to x = 40.5: five periods. The ridge under way at the start
  // (the positive one of period 0) is not counted, nor the negative ridge of period 5, still open at 40.5.
  for (int k = 0; k <= 4000; ++k) tick(m, 0.5 + 0.01 * k);
  // Crossed: negative of period 0; both ridges of periods 1 to 4; positive of period 5 (entered at
  // 40 -> 40.01 and still open at 40.5? its span is (40, 44): still open). So 1 + 8 = 9 crossings.
  EXPECT_EQ(m.crossings(), 9u);
  // Peaks: 3 (negative) five times, 2 (positive) four times.
  ASSERT_TRUE(m.felt_peak_N().has_value());
  EXPECT_NEAR(*m.felt_peak_N(), (5 * 3.0 + 4 * 2.0) / 9, 1e-9);
}

TEST(FeltPeakMeter, RidgesSteppedOverCountZero) {
  auto m = *runtime::FeltPeakMeter::for_program(program());
  // Ticks at x = 0, 5, 10, 15. 0 -> 5 passes the positive ridge (0, 4) with no tick on it: 0.
  // The negative ridge (4, 8) is read at 5 (F = -1, so 1 N) and left at 10: 1. The positive ridge
  // of period 1, (8, 12), is read at 10 (F = 2) and left at 15: 2. The negative ridge (12, 16) is
  // still open at 15.
  for (double x : {0.0, 5.0, 10.0, 15.0}) tick(m, x);
  EXPECT_EQ(m.crossings(), 3u);
  EXPECT_NEAR(*m.felt_peak_N(), (0 + 1 + 2) / 3.0, 1e-12);
}

TEST(FeltPeakMeter, AVisitThatTurnsBackIsNotACrossing) {
  auto m = *runtime::FeltPeakMeter::for_program(program());
  // Into the negative ridge (4, 8) from below and back out below it, then forward over the whole of it.
  for (double x : {3.5, 4.5, 5.5, 6.5, 5.5, 4.5, 3.5, 4.5, 5.5, 6.5, 7.5, 8.5}) tick(m, x);
  EXPECT_EQ(m.crossings(), 1u);
  // On the way over: reads at 4.5 (0.5 N), 5.5 (2 N), 6.5 (2 N), 7.5 (0.5 N).
  EXPECT_NEAR(*m.felt_peak_N(), 2.0, 1e-12);
}

TEST(FeltPeakMeter, AGapInTheTicksEndsWhatWasUnderWay) {
  auto m = *runtime::FeltPeakMeter::for_program(program());
  for (double x : {3.5, 4.5, 5.5}) tick(m, x);
  m.break_nonrt();  // ticks lost: nothing inferred about where the hand went
  for (double x : {20.5, 21.5, 22.5, 23.5, 24.5}) tick(m, x);
  // After the gap: the negative ridge of period 2, (20, 24), was under way at 20.5 (not counted);
  // nothing else was crossed whole, and the half-read ridge before the gap is dropped.
  EXPECT_EQ(m.crossings(), 0u);
  EXPECT_FALSE(m.felt_peak_N().has_value());
}

TEST(FeltPeakMeter, APositionJumpIsAGapNotThousandsOfRidges) {
  auto m = *runtime::FeltPeakMeter::for_program(program());
  // 1.25 m (1250 periods) along a 1 mm grating in one tick, a replayed or faulty position, then
  // far out: neither counts crossings, and neither hangs.
  for (double x : {3.5, 4.5, 10000.5, 10001.5, 1e300, 10002.5}) tick(m, x);
  EXPECT_EQ(m.crossings(), 0u);
}
