// Every stop cause (docs/RUNTIME.md, "Stop causes"): a device, clock or flag that triggers it, the
// force written on the tick that saw it exactly zero, nothing but zero after, and the cause named.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"

namespace sandpaper::runtime {
namespace {

using testing::program_of;
using testing::spring;
using testing::StallingClock;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Stands at (10 mm, 0) so that a spring pushes with 1 N per 100 N/m; at read `fault_at` (from 1)
// does what it is told; remembers every write and the read count at each.
class FaultDevice final : public Device {
 public:
  enum class Mode { None, ReadFails, NaNPosition, WriteFails, Jump, RaiseFlag };
  FaultDevice(Mode mode, std::size_t fault_at, DeviceFault fault = DeviceFault::None)
      : limits_(sim_device_limits()), mode_(mode), fault_at_(fault_at), fault_(fault) {
    writes.reserve(100000);
    reads_at_write.reserve(100000);
  }
  const DeviceLimits& limits() const noexcept override { return limits_; }
  bool read_position_rt(double, glm::dvec2& p) noexcept override {
    ++reads;
    p = {0.01, 0.0};
    if (reads < fault_at_ || mode_ == Mode::None) return true;
    switch (mode_) {
      case Mode::ReadFails: last_ = fault_; return false;
      case Mode::NaNPosition: p = {kNaN, 0.0}; return true;
      case Mode::Jump: p = {0.01 + 0.02 * static_cast<double>(reads - fault_at_ + 1), 0.0}; return true;  // 20 m/s
      case Mode::RaiseFlag: flag.store(true); return true;
      default: return true;
    }
  }
  bool write_force_rt(glm::dvec2 f) noexcept override {
    writes.push_back(f);
    reads_at_write.push_back(reads);
    if (mode_ == Mode::WriteFails && writes.size() == fault_at_) {
      last_ = fault_;
      return false;
    }
    return true;
  }
  DeviceFault last_fault_rt() const noexcept override { return last_; }

  std::atomic<bool> flag{false};
  std::vector<glm::dvec2> writes;
  std::vector<std::size_t> reads_at_write;
  std::size_t reads = 0;

 private:
  DeviceLimits limits_;
  Mode mode_;
  std::size_t fault_at_;
  DeviceFault fault_;
  DeviceFault last_ = DeviceFault::None;
};

ServoConfig quick() {
  ServoConfig c;
  c.rate_hz = 1000;
  c.duration_s = 1.0;
  c.ramp_s = 0;  // full force from the first tick, so that a zero after the fault means something
  return c;
}

struct Outcome {
  ServoReport report;
  std::vector<glm::dvec2> writes;
};

Outcome play(FaultDevice& device, ServoConfig c, ServoClock* clock = nullptr) {
  const auto program = program_of({spring(100.0)});
  PatchEvaluator evaluator(program);
  VirtualClock virtual_clock;
  if (device.flag.load() == false) c.stop_request = &device.flag;
  Outcome out;
  out.report = run_servo_loop(device, evaluator, clock != nullptr ? *clock : virtual_clock, c);
  out.writes = device.writes;
  return out;
}

// The ticks before `fault_tick` (from 1) pushed with the spring's -1 N; from it on, only zeros.
void expect_zero_from(const Outcome& out, std::size_t fault_tick) {
  ASSERT_GE(out.writes.size(), fault_tick);
  for (std::size_t i = 0; i + 1 < fault_tick; ++i) EXPECT_NEAR(out.writes[i].x, -1.0, 1e-9) << "tick " << i + 1;
  for (std::size_t i = fault_tick - 1; i < out.writes.size(); ++i) EXPECT_EQ(out.writes[i], glm::dvec2(0, 0)) << "write " << i + 1;
  EXPECT_EQ(out.report.ticks, fault_tick);
}

TEST(StopCauses, NamesAreStable) {
  EXPECT_STREQ(stop_cause_name(StopCause::DeviceUnplugged), "device_unplugged");
  EXPECT_STREQ(stop_cause_name(StopCause::StopRequested), "stop_requested");
  EXPECT_STREQ(stop_cause_text(StopCause::StopRequested), "stopped by signal");
  EXPECT_STREQ(stop_cause_text(StopCause::ForceNotFinite), "non-finite force");
  EXPECT_STREQ(stop_cause_name(StopCause::DeviceReset), "device_reset");
  EXPECT_STREQ(stop_cause_text(StopCause::DeviceReset), "device reset (it left the bus and came back)");
}

TEST(StopCauses, ReadFailedTimedOutAndUnpluggedAreTold) {
  const struct {
    DeviceFault fault;
    StopCause cause;
    const char* text;
  } cases[] = {{DeviceFault::None, StopCause::DeviceReadFailed, "device read failed"},
               {DeviceFault::ReadFailed, StopCause::DeviceReadFailed, "device read failed"},
               {DeviceFault::ReadTimedOut, StopCause::DeviceReadTimeout, "device read timed out"},
               {DeviceFault::Unplugged, StopCause::DeviceUnplugged, "device unplugged"}};
  for (const auto& c : cases) {
    FaultDevice device(FaultDevice::Mode::ReadFails, 5, c.fault);
    const Outcome out = play(device, quick());
    EXPECT_EQ(out.report.stop_cause, c.cause);
    EXPECT_EQ(out.report.stop_reason, c.text);
    expect_zero_from(out, 5);
  }
}

TEST(StopCauses, WriteFailedAndUnpluggedOnWrite) {
  for (const auto& [fault, cause] : {std::pair{DeviceFault::None, StopCause::DeviceWriteFailed},
                                    std::pair{DeviceFault::Unplugged, StopCause::DeviceUnplugged}}) {
    FaultDevice device(FaultDevice::Mode::WriteFails, 4, fault);
    const Outcome out = play(device, quick());
    EXPECT_EQ(out.report.stop_cause, cause);
    // The failed write was the 4th tick's force; the very next write (the closing one) is zero.
    ASSERT_EQ(out.writes.size(), 5u);
    EXPECT_EQ(out.writes[4], glm::dvec2(0, 0));
    EXPECT_EQ(out.report.ticks, 4u);
  }
}

TEST(StopCauses, NonFinitePosition) {
  FaultDevice device(FaultDevice::Mode::NaNPosition, 7);
  const Outcome out = play(device, quick());
  EXPECT_EQ(out.report.stop_cause, StopCause::PositionNotFinite);
  EXPECT_EQ(out.report.stop_reason, "non-finite position");
  expect_zero_from(out, 7);
}

TEST(StopCauses, NonFiniteForce) {
  const auto program = program_of({spring(100.0), testing::grating(0.003, 0.0, {1.0f, std::nanf("")})});
  PatchEvaluator evaluator(program);
  FaultDevice device(FaultDevice::Mode::None, 0);
  VirtualClock clock;
  const ServoReport report = run_servo_loop(device, evaluator, clock, quick());
  EXPECT_EQ(report.stop_cause, StopCause::ForceNotFinite);
  ASSERT_FALSE(device.writes.empty());
  for (const glm::dvec2 f : device.writes) EXPECT_EQ(f, glm::dvec2(0, 0));
}

TEST(StopCauses, VelocityLimit) {
  // From read 10 the hand jumps 20 mm a tick (20 m/s); the 50 Hz velocity filter passes about a
  // quarter of a step at once, so the limit of 2 m/s is crossed on the first tick of the jump.
  FaultDevice device(FaultDevice::Mode::Jump, 10);
  const Outcome out = play(device, quick());
  EXPECT_EQ(out.report.stop_cause, StopCause::VelocityLimit);
  EXPECT_EQ(out.report.stop_reason, "velocity limit exceeded");
  expect_zero_from(out, 10);

  // A higher limit lets the same run go on: the limit, not the jump, stopped it.
  FaultDevice again(FaultDevice::Mode::Jump, 10);
  ServoConfig lax = quick();
  lax.velocity_limit_m_s = 1000;
  lax.duration_s = 0.02;
  EXPECT_EQ(play(again, lax).report.stop_cause, StopCause::Completed);
}

TEST(StopCauses, DeadlineMissedForLongerThanAllowed) {
  // Stalled 80 ms after waking for tick 6 (index 5): that tick starts 80 ms late, over the 50 ms allowed.
  FaultDevice device(FaultDevice::Mode::None, 0);
  StallingClock clock(5, 80'000'000);
  const Outcome out = play(device, quick(), &clock);
  EXPECT_EQ(out.report.stop_cause, StopCause::DeadlineMissed);
  EXPECT_EQ(out.report.stop_reason, "servo deadline missed");
  expect_zero_from(out, 6);
  EXPECT_EQ(device.reads, 5u);  // the late tick did not even read: it only zeroed the force

  // A 30 ms stall is an overrun but within the allowance: the run completes.
  FaultDevice tolerated(FaultDevice::Mode::None, 0);
  StallingClock short_stall(5, 30'000'000);
  ServoConfig c = quick();
  c.duration_s = 0.1;
  const Outcome ok = play(tolerated, c, &short_stall);
  EXPECT_EQ(ok.report.stop_cause, StopCause::Completed);
  EXPECT_GT(ok.report.overruns, 0u);
}

TEST(StopCauses, StallsAreCountedAndTheGuardCountsPeriods) {
  // A 30 ms stall at 1 kHz completes (under the default 50 ms guard) but is reported: one stall,
  // its gap the 31 ms between tick 5's start and the late tick 6's start.
  FaultDevice slow(FaultDevice::Mode::None, 0);
  StallingClock stall(5, 30'000'000);
  ServoConfig c = quick();
  c.duration_s = 0.1;
  const Outcome once = play(slow, c, &stall);
  EXPECT_EQ(once.report.stop_cause, StopCause::Completed);
  EXPECT_EQ(once.report.stalls, 1u);
  EXPECT_DOUBLE_EQ(once.report.longest_stall_us, 31'000.0);

  // Four periods late is no stall; the gap must exceed kStallPeriods periods.
  FaultDevice brief(FaultDevice::Mode::None, 0);
  StallingClock short_stall(5, 3'900'000);
  EXPECT_EQ(play(brief, c, &short_stall).report.stalls, 0u);

  // The same 30 ms at 10 kHz (300 periods) is also under the default guard, which is in time ...
  FaultDevice fast(FaultDevice::Mode::None, 0);
  StallingClock fast_stall(5, 30'000'000);
  ServoConfig ten_khz = c;
  ten_khz.rate_hz = 10'000;
  const Outcome tolerated = play(fast, ten_khz, &fast_stall);
  EXPECT_EQ(tolerated.report.stop_cause, StopCause::Completed);
  EXPECT_EQ(tolerated.report.stalls, 1u);
  // ... and a guard set in periods stops it: 200 periods at 10 kHz is 20 ms.
  FaultDevice tight(FaultDevice::Mode::None, 0);
  StallingClock tight_stall(5, 30'000'000);
  ten_khz.deadline_guard_periods = 200;
  EXPECT_EQ(play(tight, ten_khz, &tight_stall).report.stop_cause, StopCause::DeadlineMissed);
  // 400 periods (40 ms) lets it through again: the threshold, not the stall, decides.
  FaultDevice wide(FaultDevice::Mode::None, 0);
  StallingClock wide_stall(5, 30'000'000);
  ten_khz.deadline_guard_periods = 400;
  EXPECT_EQ(play(wide, ten_khz, &wide_stall).report.stop_cause, StopCause::Completed);
}

TEST(StopCauses, StopRequestedBySignalFlag) {
  // The flag goes up during read 8 (as a signal handler would set it); tick 9 sees it.
  FaultDevice device(FaultDevice::Mode::RaiseFlag, 8);
  const Outcome out = play(device, quick());
  EXPECT_EQ(out.report.stop_cause, StopCause::StopRequested);
  EXPECT_EQ(out.report.stop_reason, "stopped by signal");
  expect_zero_from(out, 9);
}

TEST(SafetyRamp, ForceRampsUpFromZeroAtStart) {
  const auto program = program_of({spring(100.0)});
  PatchEvaluator evaluator(program);
  FaultDevice device(FaultDevice::Mode::None, 0);
  VirtualClock clock;
  ServoConfig c = quick();
  c.ramp_s = 0.05;
  c.duration_s = 0.1;
  const ServoReport report = run_servo_loop(device, evaluator, clock, c);
  ASSERT_EQ(report.stop_cause, StopCause::Completed);
  ASSERT_EQ(device.writes.size(), 101u);
  EXPECT_EQ(device.writes[0], glm::dvec2(0, 0));       // t = 0
  EXPECT_NEAR(device.writes[25].x, -0.5, 1e-9);         // t = 25 ms: half
  EXPECT_NEAR(device.writes[50].x, -1.0, 1e-9);         // t = 50 ms: full
  for (std::size_t k = 1; k < 50; ++k) EXPECT_LT(std::abs(device.writes[k].x), 1.0) << k;
  EXPECT_EQ(report.ramped_ticks, 50u);
}

TEST(SafetyClamp, ForceNeverExceedsTheDeviceMaximumAndIsCounted) {
  const auto program = program_of({spring(5000.0)});  // 50 N at 10 mm, the sim allows 10 N
  PatchEvaluator evaluator(program);
  FaultDevice device(FaultDevice::Mode::None, 0);
  VirtualClock clock;
  ServoConfig c = quick();
  c.duration_s = 0.05;
  const ServoReport report = run_servo_loop(device, evaluator, clock, c);
  EXPECT_EQ(report.clamped_ticks, 50u);
  for (const glm::dvec2 f : device.writes) EXPECT_LE(std::hypot(f.x, f.y), 10.0 + 1e-12);
  EXPECT_NEAR(report.felt_max_lateral_force_N, 10.0, 1e-12);
}

}  // namespace
}  // namespace sandpaper::runtime
