// The servo loop's velocity estimate from a device whose positions do not come every tick: a USB
// joystick's reports delayed and delivered in a burst, and a device that reports only on change.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <vector>

#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"

namespace sandpaper::runtime {
namespace {

// A hand scanning along x at `speed_m_s` until `stop_s`, then standing. The device's report
// reaches the tick only at every `every`-th read (the transport delivered a burst; the tick sees
// the latest) while moving, and not at all once standing (a device that reports only on change);
// the reads between hold the last position. `tell_freshness` false: the device does not say which
// reads were fresh (the Device default), as the loop saw every USB joystick before.
class BurstDevice final : public Device {
 public:
  BurstDevice(double speed_m_s, std::size_t every, double stop_s, bool tell_freshness)
      : limits_(sim_device_limits()), speed_(speed_m_s), every_(every), stop_s_(stop_s), tell_(tell_freshness) {}
  const DeviceLimits& limits() const noexcept override { return limits_; }
  bool read_position_rt(double t_s, glm::dvec2& p) noexcept override {
    fresh_ = t_s <= stop_s_ && reads_++ % every_ == 0;
    if (fresh_) held_ = {speed_ * t_s, 0.0};
    p = held_;
    return true;
  }
  bool position_fresh_rt() const noexcept override { return tell_ ? fresh_ : true; }
  bool write_force_rt(glm::dvec2) noexcept override { return true; }

 private:
  DeviceLimits limits_;
  double speed_;
  std::size_t every_;
  double stop_s_;
  bool tell_;
  std::size_t reads_ = 0;
  bool fresh_ = false;
  glm::dvec2 held_{0, 0};
};

// Plays nothing; keeps the velocity the loop gave each tick.
class VelocityProbe final : public ForceSource {
 public:
  explicit VelocityProbe(std::size_t ticks) { velocity_x.reserve(ticks); }
  glm::dvec2 force_rt(const HandState& hand, double) noexcept override {
    if (velocity_x.size() < velocity_x.capacity()) velocity_x.push_back(hand.velocity_m_s.x);
    return {0, 0};
  }
  void reset_rt(const HandState&) noexcept override {}
  std::vector<double> velocity_x;
};

struct Played {
  ServoReport report;
  std::vector<double> velocity_x;  // per tick, m/s
};

Played play(BurstDevice& device, double duration_s) {
  ServoConfig c;
  c.rate_hz = 1000;
  c.duration_s = duration_s;
  VelocityProbe probe(static_cast<std::size_t>(duration_s * c.rate_hz) + 1);
  VirtualClock clock;
  Played out;
  out.report = run_servo_loop(device, probe, clock, c);
  out.velocity_x = probe.velocity_x;
  return out;
}

TEST(ServoVelocity, PositionsInBurstsReadAsTheHandsSpeed) {
  // 0.25 m/s with a report reaching the tick every 40 ms: 10 mm between fresh positions. Taken one
  // tick apart (the loop before Device::position_fresh_rt), 10 m/s through the 50 Hz filter's gain
  // of 1 ms / (1 ms + 3.18 ms) is 2.4 m/s: over the 2 m/s velocity limit, and the run stops.
  BurstDevice blind(0.25, 40, 10.0, false);
  EXPECT_EQ(play(blind, 0.5).report.stop_cause, StopCause::VelocityLimit);

  // Over the 40 ms between them, 10 mm is the hand's 0.25 m/s: the run plays on, and after three
  // fresh positions the estimate is within 1 % (the filter's gain over 40 ms is 0.926 a step).
  BurstDevice burst(0.25, 40, 10.0, true);
  const Played out = play(burst, 0.5);
  EXPECT_EQ(out.report.stop_cause, StopCause::Completed);
  ASSERT_EQ(out.velocity_x.size(), 500u);
  for (std::size_t k = 125; k < out.velocity_x.size(); ++k) EXPECT_NEAR(out.velocity_x[k], 0.25, 0.0025) << "tick " << k;
}

TEST(ServoVelocity, AHandThatStopsReadsAsStillOnceTheHoldHasPassed) {
  // Fresh every tick at 0.1 m/s for 200 ms, then nothing fresh: the estimate holds 0.1 m/s for the
  // 50 ms hold (the last reports may only be late), then a still hand counts (0 over 51 ms: gain
  // 0.941, 5.9 mm/s left; after the next hold 0.35 mm/s).
  BurstDevice device(0.1, 1, 0.2, true);
  const Played out = play(device, 0.5);
  EXPECT_EQ(out.report.stop_cause, StopCause::Completed);
  ASSERT_EQ(out.velocity_x.size(), 500u);
  EXPECT_NEAR(out.velocity_x[190], 0.1, 1e-3);
  EXPECT_NEAR(out.velocity_x[240], 0.1, 1e-3);
  EXPECT_LT(std::abs(out.velocity_x[260]), 0.01);
  for (std::size_t k = 320; k < out.velocity_x.size(); ++k) EXPECT_LT(std::abs(out.velocity_x[k]), 1e-3) << "tick " << k;
}

TEST(ServoVelocity, AHoldThatIsNotATimeIsRefusedBeforeTheRun) {
  for (double hold : {-0.01, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    BurstDevice device(0.1, 1, 1.0, true);
    VelocityProbe probe(10);
    VirtualClock clock;
    ServoConfig c;
    c.duration_s = 0.005;
    c.velocity_hold_s = hold;
    EXPECT_THROW(run_servo_loop(device, probe, clock, c), std::invalid_argument) << hold;
    EXPECT_TRUE(probe.velocity_x.empty()) << "a refused run played " << probe.velocity_x.size() << " ticks";
  }
}

}  // namespace
}  // namespace sandpaper::runtime
