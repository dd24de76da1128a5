// The lab's scripted hand (usb-lab/device/scripted_hand.hpp), sampled as the firmware samples it:
// once a control step at 1 kHz.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "scripted_hand.hpp"

using namespace sandpaper::usb_lab;

namespace {

constexpr double kRateHz = 1000;

HandPath scan(double speed_m_s, double spread_m) {
  HandPath p;
  p.kind = "scan";
  p.speed_m_s = speed_m_s;
  p.extent_m = 0.04;
  p.turn_spread_m = spread_m;
  return p;
}

// Per stroke (between turns), where the firmware's samples sit within one step (speed / rate):
// the fraction of a step by which the stroke's samples are offset from 0 (0..1).
std::vector<double> stroke_phases(const HandPath& path, double seconds) {
  ScriptedHand hand(path);
  const double step = path.speed_m_s / kRateHz;
  std::vector<double> phases;
  double last = hand.at(0).x_m, direction = 1;
  bool first = true;
  for (int k = 1; k < seconds * kRateHz; ++k) {
    const double x = hand.at(k / kRateHz).x_m;
    const double d = x > last ? 1 : -1;
    if (d != direction || first) {
      // The second sample after a turn is a whole step past the first, so its offset is the stroke's.
      const double f = x / step - std::floor(x / step);
      phases.push_back(std::min(f, 1 - f) < 1e-9 ? 0 : f);
      direction = d;
      first = false;
    }
    last = x;
  }
  return phases;
}

// The Kolmogorov-Smirnov distance of the offsets from the uniform distribution on [0, 1).
double ks_from_uniform(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const double n = static_cast<double>(v.size());
  double d = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
    d = std::max({d, static_cast<double>(i + 1) / n - v[i], v[i] - static_cast<double>(i) / n});
  return d;
}

}  // namespace

// 40 mm at 100 mm/s is 400 steps: without spread every stroke's samples fall on the same places.
TEST(ScriptedHand, StrokesOfOneWholeNumberOfStepsMeetTheSamePlaces) {
  const auto phases = stroke_phases(scan(0.1, 0), 20);
  ASSERT_GE(phases.size(), 40u);
  for (double f : phases) EXPECT_NEAR(std::min(f, 1 - f), 0, 1e-6);
  EXPECT_GT(ks_from_uniform(phases), 0.95);
}

// With the turn points spread, the strokes' samples fall at offsets spread evenly within a step:
// over 50 strokes their distribution is within a Kolmogorov-Smirnov distance of 0.2 of the uniform
// one (the 5 % critical value for 50 samples is 0.19; unspread strokes are at distance 1), at
// speeds whose step divides corduroy's 3.2 mm period (100, 200 mm/s) and at one whose does not.
TEST(ScriptedHand, SpreadTurnPointsPutEachStrokesSamplesAtANewOffset) {
  for (double speed : {0.1, 0.2, 0.0731}) {
    const auto phases = stroke_phases(scan(speed, 1e-3), 0.04 * 52 / speed);
    ASSERT_GE(phases.size(), 50u) << speed;
    EXPECT_LT(ks_from_uniform(phases), 0.2) << speed;
  }
}

// The hand stays a hand: it never moves more than speed / rate between steps (no jump at a turn),
// and turns within [extent/2, extent/2 + spread] of the centre.
TEST(ScriptedHand, TurnsWithinTheSpreadAndNeverJumps) {
  HandPath p = scan(0.2, 1e-3);
  p.centre_x_m = 0.005;
  ScriptedHand hand(p);
  double last = hand.at(0).x_m, lo = last, hi = last;
  EXPECT_DOUBLE_EQ(last, 0.005 - 0.02);
  for (int k = 1; k < 30 * kRateHz; ++k) {
    const double x = hand.at(k / kRateHz).x_m;
    EXPECT_LE(std::abs(x - last), p.speed_m_s / kRateHz + 1e-12);
    lo = std::min(lo, x), hi = std::max(hi, x);
    last = x;
  }
  EXPECT_GE(lo, 0.005 - 0.021 - 1e-12);
  EXPECT_LE(hi, 0.005 + 0.021 + 1e-12);
  EXPECT_GT(hi - lo, 0.040);  // some turn went beyond the extent
}

TEST(ScriptedHand, RefusesWhatIsNoPath) {
  HandPath p = scan(0.1, -1e-3);
  EXPECT_THROW(ScriptedHand{p}, std::invalid_argument);
  p.turn_spread_m = 0;
  p.speed_m_s = 0;
  EXPECT_THROW(ScriptedHand{p}, std::invalid_argument);
  p.kind = "zigzag";
  p.speed_m_s = 0.1;
  EXPECT_THROW(ScriptedHand{p}, std::invalid_argument);
}
