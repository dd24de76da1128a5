// Hot swap (docs/RUNTIME.md, "Hot swap"): force continuity across a change of material, the old
// source freed off the servo thread, many swaps under a running servo thread, and no allocation
// or lock on the servo thread while swapping.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include <glm/geometric.hpp>

#include "allocation_counter.hpp"
#include "runtime_test_support.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/runtime/swappable_source.hpp"

namespace sandpaper::runtime {
namespace {

using testing::grating;
using testing::program_of;
using testing::spring;

// Two stateless materials, so "each material's own force over the same hand path" is well defined:
// A, a 2 mm grating of 1 N; B, the same grating turned 90 degrees plus a constant 3 N push.
schema::PatchProgram material_a() {
  std::vector<float> table(64);
  for (std::size_t i = 0; i < table.size(); ++i) table[i] = static_cast<float>(std::sin(6.283185307 * static_cast<double>(i) / 64.0));
  return program_of({grating(0.002, 0.0, table)});
}
schema::PatchProgram material_b() {
  auto p = material_a();
  std::get<schema::GratingTerm>(p.terms[0]).orientation_rad = 1.5707963;
  schema::ConstantForceTerm push;
  push.force_N[0] = 3.0;
  push.force_N[1] = 0.0;
  p.terms.push_back(push);
  return p;
}

constexpr double kDt = 0.001;  // 1 kHz
constexpr std::size_t kTicks = 400;
constexpr std::size_t kSwapTick = 200;

HandState hand_at(std::size_t k) {
  const SimJoystick path(sim_device_limits(), HandScript{HandPath::Circle, 0.05, 0.02, 0.0}, 0);
  HandState h;
  h.position_m = path.hand_position(static_cast<double>(k) * kDt);
  h.velocity_m_s = (h.position_m - path.hand_position(static_cast<double>(k) * kDt - kDt)) / kDt;
  return h;
}

std::vector<glm::dvec2> play_alone(const schema::PatchProgram& program) {
  PatchEvaluator e(program);
  e.reset_rt(hand_at(0));
  std::vector<glm::dvec2> f;
  for (std::size_t k = 0; k < kTicks; ++k) f.push_back(e.force_rt(hand_at(k), k == 0 ? 0.0 : kDt));
  return f;
}

// Plays A, offers B just before tick kSwapTick, returns every tick's force.
std::vector<glm::dvec2> play_swapping(const schema::PatchProgram& a, const schema::PatchProgram& b, double crossfade_s) {
  SwappableSource source(std::make_unique<PatchEvaluator>(a), crossfade_s);
  source.reset_rt(hand_at(0));
  std::vector<glm::dvec2> f;
  for (std::size_t k = 0; k < kTicks; ++k) {
    if (k == kSwapTick) source.offer_nonrt(std::make_unique<PatchEvaluator>(b));
    f.push_back(source.force_rt(hand_at(k), k == 0 ? 0.0 : kDt));
  }
  EXPECT_EQ(source.swaps_picked_up(), 1u);
  EXPECT_EQ(source.collect_retired_nonrt(), 1u);  // A came back to be freed here
  return f;
}

double largest_step(const std::vector<glm::dvec2>& f, std::size_t from, std::size_t to) {
  double step = 0;
  for (std::size_t k = std::max<std::size_t>(from, 1); k < to; ++k) step = std::max(step, glm::length(f[k] - f[k - 1]));
  return step;
}

TEST(HotSwap, ForceStepsAcrossASwapStayWithinTheMaterialsOwn) {
  const auto a = material_a(), b = material_b();
  const auto fa = play_alone(a), fb = play_alone(b);
  const double own = std::max(largest_step(fa, 1, kTicks), largest_step(fb, 1, kTicks));

  const double crossfade_s = 0.005;
  const auto swapped = play_swapping(a, b, crossfade_s);
  const std::size_t fade_end = kSwapTick + 6;  // a = 0, 0.2, ..., 1 at 1 kHz
  // Blend margin. With F = (1 - a) F_A + a F_B, the step between ticks is
  // (1 - a) dF_A + a dF_B + da (F_B - F_A): the first two are at most the materials' own largest
  // step (a convex combination), the last at most da * max |F_B - F_A| with da = dt / crossfade.
  double gap = 0;
  for (std::size_t k = kSwapTick - 1; k <= fade_end; ++k) gap = std::max(gap, glm::length(fb[k] - fa[k]));
  const double margin = kDt / crossfade_s * gap;
  const double during = largest_step(swapped, kSwapTick, fade_end + 1);
  EXPECT_LE(during, own + margin + 1e-9) << "own " << own << " margin " << margin;
  // Before the swap the output is A's; after the fade, B's.
  EXPECT_EQ(swapped[kSwapTick - 1], fa[kSwapTick - 1]);
  for (std::size_t k = fade_end; k < kTicks; ++k) EXPECT_NEAR(glm::length(swapped[k] - fb[k]), 0.0, 1e-12) << k;

  // Without the crossfade the same swap steps by |F_B - F_A| at once, far beyond that bound: the
  // bound above is one a missing or broken blend fails.
  const auto abrupt = play_swapping(a, b, 0.0);
  const double jump = largest_step(abrupt, kSwapTick, kSwapTick + 2);
  EXPECT_GT(jump, own + margin) << "own " << own << " margin " << margin;
  EXPECT_GT(jump, 2.0);
}

// Records which thread ran it and which destroyed it.
struct ProbeLog {
  std::atomic<int> created{0}, destroyed{0}, destroyed_on_servo{0};
  std::atomic<std::thread::id> servo{};
};

class ProbeSource final : public ForceSource {
 public:
  ProbeSource(ProbeLog& log, double fx, std::mutex* lock_me = nullptr) : log_(log), fx_(fx), lock_me_(lock_me) { ++log_.created; }
  ~ProbeSource() override {
    if (std::this_thread::get_id() == log_.servo.load()) ++log_.destroyed_on_servo;
    ++log_.destroyed;
  }
  glm::dvec2 force_rt(const HandState&, double) noexcept override {
    log_.servo.store(std::this_thread::get_id(), std::memory_order_relaxed);
    if (lock_me_ != nullptr) {
      lock_me_->lock();
      lock_me_->unlock();
    }
    return {fx_, 0};
  }
  void reset_rt(const HandState&) noexcept override {}

 private:
  ProbeLog& log_;
  double fx_;
  std::mutex* lock_me_;
};

ServoConfig loose_config(double duration_s) {
  ServoConfig c;
  c.rate_hz = 1000;
  c.duration_s = duration_s;
  c.deadline_guard_periods = 10000;  // a busy test machine must not stop the run: timing is not what is tested
  return c;
}

TEST(HotSwap, TheOldSourceIsFreedOffTheServoThread) {
  ProbeLog log;
  SimJoystick joystick(sim_device_limits(), HandScript{}, 1000);
  SwappableSource source(std::make_unique<ProbeSource>(log, 1.0));
  ServoThread servo;
  servo.start_nonrt(joystick, source, loose_config(0.5));
  while (log.servo.load() == std::thread::id{} && !servo.finished()) std::this_thread::yield();
  source.offer_nonrt(std::make_unique<ProbeSource>(log, 2.0));
  std::size_t freed = 0;
  while (freed == 0 && !servo.finished()) {
    freed += source.collect_retired_nonrt();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const ServoReport report = servo.join_nonrt();
  EXPECT_EQ(report.stop_cause, StopCause::Completed);
  EXPECT_EQ(freed, 1u);
  EXPECT_EQ(log.destroyed.load(), 1);
  EXPECT_NE(log.servo.load(), std::this_thread::get_id());
  EXPECT_EQ(log.destroyed_on_servo.load(), 0);
}

TEST(HotSwap, ManySwapsUnderARunningServoThread) {
  ProbeLog log;
  SimJoystick joystick(sim_device_limits(), HandScript{}, 2000);
  {
    SwappableSource source(std::make_unique<ProbeSource>(log, 0.0), 0.002);
    ServoThread servo;
    servo.start_nonrt(joystick, source, loose_config(1.0));
    int offered = 0;
    while (!servo.finished()) {
      source.offer_nonrt(std::make_unique<ProbeSource>(log, 1.0 + offered % 3));
      ++offered;
      source.collect_retired_nonrt();
      std::this_thread::sleep_for(std::chrono::microseconds(700));
    }
    const ServoReport report = servo.join_nonrt();
    EXPECT_EQ(report.stop_cause, StopCause::Completed);
    EXPECT_GT(source.swaps_picked_up(), 20u);
    EXPECT_GT(offered, 20);
  }
  EXPECT_EQ(log.destroyed.load(), log.created.load());  // nothing leaked, nothing freed twice
  EXPECT_EQ(log.destroyed_on_servo.load(), 0);
  // A blend of two equal forces may round one ulp above them: (1 - a) 3 + a 3 = 3.0000000000000004.
  for (const auto& r : joystick.records())
    ASSERT_TRUE(r.force_N.x >= 0 && r.force_N.x <= 3.0 + 1e-12) << r.t_s << " s: " << r.force_N.x << " N";
}

// The servo loop on a thread of the test's own, so that the counters can be armed on it.
sandpaper::test::RtViolations run_counted(Device& device, ForceSource& source, const ServoConfig& config, ServoReport& report) {
  sandpaper::test::RtViolations seen;
  std::thread servo([&] {
    sandpaper::test::CountedRtViolations counting;
    MonotonicClock clock;
    report = run_servo_loop(device, source, clock, config);
    seen = counting.stop();
  });
  servo.join();
  return seen;
}

TEST(HotSwap, SwappingNeitherAllocatesNorLocksOnTheServoThread) {
  ProbeLog log;
  SimJoystick joystick(sim_device_limits(), HandScript{}, 1000);
  SwappableSource source(std::make_unique<ProbeSource>(log, 0.0));
  ServoReport report;
  std::atomic<bool> done{false};
  std::thread application([&] {
    int k = 0;
    while (!done.load()) {
      source.offer_nonrt(std::make_unique<ProbeSource>(log, 1.0 + k++ % 2));
      source.collect_retired_nonrt();
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  });
  const sandpaper::test::RtViolations seen = run_counted(joystick, source, loose_config(0.4), report);
  done = true;
  application.join();
  EXPECT_EQ(report.stop_cause, StopCause::Completed);
  EXPECT_GT(source.swaps_picked_up(), 10u);
  EXPECT_LE(seen.allocations, 2u);  // the loop's two timing arrays, before the first tick
  EXPECT_EQ(seen.locks, 0u);
}

}  // namespace
}  // namespace sandpaper::runtime
