// The servo tick must never allocate. run_servo_loop allocates its timing arrays before the first
// tick, so this test counts every allocation a whole run makes and checks the count does not grow
// with the number of ticks: any allocation inside the tick would add one per tick.
//
// Allocations are counted by tests/support/allocation_counter (global operator new replaced for
// this executable, counting only on the thread that armed it).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <mutex>
#include <new>
#include <string>
#include <thread>
#include <variant>

#include "allocation_counter.hpp"
#include "runtime_test_support.hpp"
#include "term_samples.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"

namespace sandpaper::runtime {
namespace {

using sandpaper::test::CountedAllocations;
using sandpaper::test::CountedRtViolations;
using sandpaper::test::RtViolations;

using testing::damper;
using testing::grating;
using testing::program_of;
using testing::spring;

schema::HeightFieldTerm ripple_field() {
  schema::HeightFieldTerm field;
  field.nx = field.ny = 64;
  field.origin_m[0] = field.origin_m[1] = -0.04;
  field.spacing_m[0] = field.spacing_m[1] = 0.00125;
  field.repeat = true;
  for (std::uint32_t i = 0; i < field.nx * field.ny; ++i) {
    field.force_x_N.push_back(static_cast<float>(i % 7) - 3.0f);
    field.force_y_N.push_back(static_cast<float>(i % 5) - 2.0f);
  }
  return field;
}

schema::PatchProgram table_program() {
  std::vector<float> table(256);
  for (std::size_t i = 0; i < table.size(); ++i) table[i] = static_cast<float>(i % 32) * 0.1f;
  return program_of({spring(400.0), damper(2.0), grating(0.0025, 0.4, table), ripple_field()});
}

// One term of every kind, stateful ones included, with a tank small enough to run dry and scale.
schema::PatchProgram every_kind_program() {
  auto program = program_of(testing::every_term_kind());
  program.energy_budget_J = 0.001;
  program.energy_refill_W = 0.002;
  return program;
}

// Allocations made by one complete run of `ticks` ticks, everything else built beforehand.
std::size_t allocations_in_run(const schema::PatchProgram& program, std::uint64_t ticks) {
  PatchEvaluator evaluator(program);
  SimJoystick joystick(sim_device_limits(), HandScript{HandPath::Circle, 0.08, 0.03, 0.0}, ticks);
  VirtualClock clock;
  ServoConfig config;
  config.rate_hz = 1000;
  config.duration_s = static_cast<double>(ticks) / config.rate_hz;

  std::size_t count = 0;
  {
    CountedAllocations counting;
    const ServoReport report = run_servo_loop(joystick, evaluator, clock, config);
    count = counting.stop();  // before the checks: gtest's own assertions allocate
    EXPECT_EQ(report.ticks, ticks);
    EXPECT_EQ(report.stop_reason, "completed");
  }
  EXPECT_EQ(joystick.records().size(), ticks);
  return count;
}

TEST(ServoNoAllocation, TheCounterSeesAnAllocation) {
  std::size_t count = 0;
  {
    CountedAllocations counting;
    int* volatile probe = new int(7);
    delete probe;
    count = counting.stop();
  }
  EXPECT_EQ(count, 1u);
}

TEST(ServoNoAllocation, AllocationsDoNotGrowWithTicks) {
  const auto program = table_program();
  const std::size_t short_run = allocations_in_run(program, 1000);
  const std::size_t long_run = allocations_in_run(program, 20000);
  EXPECT_EQ(short_run, long_run);
  // The two timing histograms; a tick that allocated only once (a string growing on first use, say)
  // would not grow with the ticks but would show up here.
  EXPECT_LE(short_run, 2u);
}

// A device that raises the stop flag after a given number of reads: a run "until stopped" ends.
class StopAfter final : public Device {
 public:
  StopAfter(std::atomic<bool>& flag, std::uint64_t reads) : flag_(flag), reads_left_(reads) {}
  const DeviceLimits& limits() const noexcept override { return limits_; }
  bool read_position_rt(double, glm::dvec2& p) noexcept override {
    p = {0, 0};
    if (reads_left_ > 0 && --reads_left_ == 0) flag_.store(true, std::memory_order_relaxed);
    return true;
  }
  bool write_force_rt(glm::dvec2) noexcept override { return true; }

 private:
  DeviceLimits limits_ = sim_device_limits();
  std::atomic<bool>& flag_;
  std::uint64_t reads_left_;
};

// Bytes the servo loop allocates for a run at `rate_hz` of `duration_s` (0: until stopped, after
// `stop_after` ticks).
std::size_t bytes_in_run(double rate_hz, double duration_s, std::uint64_t stop_after) {
  const auto program = table_program();
  PatchEvaluator evaluator(program);
  std::atomic<bool> stop{false};
  StopAfter device(stop, stop_after);
  VirtualClock clock;
  ServoConfig config;
  config.rate_hz = rate_hz;
  config.duration_s = duration_s;
  config.stop_request = &stop;
  CountedAllocations counting;
  const ServoReport report = run_servo_loop(device, evaluator, clock, config);
  const std::size_t bytes = counting.bytes();
  counting.stop();
  // Stopped runs play one more tick: the one that sees the flag and writes zero.
  EXPECT_EQ(report.ticks, duration_s > 0 ? static_cast<std::uint64_t>(std::llround(duration_s * rate_hz)) : stop_after + 1);
  return bytes;
}

TEST(ServoNoAllocation, MemoryDoesNotGrowWithRunLength) {
  for (double rate : {1000.0, 10000.0}) {
    SCOPED_TRACE(rate);
    const std::size_t one_second = bytes_in_run(rate, 1.0, 0);
    // A minute of servo time, and a run until stopped that went on for 30 s before the stop.
    EXPECT_EQ(bytes_in_run(rate, 60.0, 0), one_second);
    // (plus the stop reason's text, "stopped by signal", one short string after the loop)
    EXPECT_LE(bytes_in_run(rate, 0.0, static_cast<std::uint64_t>(30 * rate)), one_second + 32);
    // The timing statistics are two fixed histograms (80 KB), whatever the rate: not 16 bytes a tick.
    EXPECT_LE(one_second, 100'000u);
  }
}

// Every term kind: the stateful ones advance state in slots the constructor allocated, and the
// energy tank meters the non-passive ones, all without allocating.
TEST(ServoNoAllocation, EveryTermKindRunsWithoutAllocating) {
  const auto program = every_kind_program();
  ASSERT_EQ(program.terms.size(), std::variant_size_v<schema::Term>);
  const std::size_t short_run = allocations_in_run(program, 1000);
  const std::size_t long_run = allocations_in_run(program, 20000);
  EXPECT_EQ(short_run, long_run);
  EXPECT_LE(short_run, 2u);
}

// Wraps a force source; optionally locks a std::mutex or mallocs inside force_rt, as a careless
// material might. The detection tests below use it to show that the counters really see these.
class MisbehavingSource final : public ForceSource {
 public:
  MisbehavingSource(ForceSource& inner, std::mutex* lock_me, bool malloc_each_tick)
      : inner_(inner), lock_me_(lock_me), malloc_(malloc_each_tick) {}
  glm::dvec2 force_rt(const HandState& hand, double dt_s) noexcept override {
    if (lock_me_ != nullptr) {
      const std::lock_guard<std::mutex> guard(*lock_me_);
      touched_ = touched_ + 1;
    }
    if (malloc_) {
      void* volatile p = std::malloc(16);
      std::free(p);
    }
    return inner_.force_rt(hand, dt_s);
  }
  void reset_rt(const HandState& hand) noexcept override { inner_.reset_rt(hand); }

 private:
  ForceSource& inner_;
  std::mutex* lock_me_;
  bool malloc_;
  volatile int touched_ = 0;
};

// One run of `ticks` on a thread of its own (the servo thread), counting only there.
RtViolations violations_in_run(ForceSource& source, std::uint64_t ticks) {
  SimJoystick joystick(sim_device_limits(), HandScript{HandPath::Circle, 0.08, 0.03, 0.0}, ticks);
  ServoConfig config;
  config.duration_s = static_cast<double>(ticks) / config.rate_hz;
  RtViolations seen;
  ServoReport report;
  std::thread servo([&] {
    CountedRtViolations counting;
    VirtualClock clock;
    report = run_servo_loop(joystick, source, clock, config);
    seen = counting.stop();
  });
  servo.join();
  EXPECT_EQ(report.stop_reason, "completed");
  return seen;
}

TEST(ServoNoLock, TheTickNeitherAllocatesNorLocks) {
  const auto program = every_kind_program();
  PatchEvaluator evaluator(program);
  const RtViolations seen = violations_in_run(evaluator, 5000);
  EXPECT_EQ(seen.locks, 0u);
  EXPECT_LE(seen.allocations, 2u);  // the two timing arrays, before the first tick
}

TEST(ServoNoLock, AStdMutexLockedInForceRtIsCaught) {
  if (!test::counts_c_allocations_and_locks()) GTEST_SKIP() << "sanitizer build: malloc and mutexes belong to the sanitizer";
  const auto program = table_program();
  PatchEvaluator evaluator(program);
  std::mutex mutex;
  MisbehavingSource locking(evaluator, &mutex, false);
  const RtViolations seen = violations_in_run(locking, 500);
  EXPECT_GE(seen.locks, 500u);  // one per tick at least
  EXPECT_LE(seen.allocations, 2u);
}

TEST(ServoNoLock, AMallocInForceRtIsCaught) {
  if (!test::counts_c_allocations_and_locks()) GTEST_SKIP() << "sanitizer build: malloc and mutexes belong to the sanitizer";
  const auto program = table_program();
  PatchEvaluator evaluator(program);
  MisbehavingSource allocating(evaluator, nullptr, true);
  const RtViolations seen = violations_in_run(allocating, 500);
  EXPECT_GE(seen.allocations, 502u);
  EXPECT_EQ(seen.locks, 0u);
}

TEST(ServoNoLock, OtherThreadsAreNotCounted) {
  if (!test::counts_c_allocations_and_locks()) GTEST_SKIP() << "sanitizer build: malloc and mutexes belong to the sanitizer";
  // Starting a thread allocates on this thread (std::thread's state, glibc's thread bookkeeping):
  // the same for a thread that does nothing and for one that locks and allocates, as only this
  // thread is counted.
  std::mutex mutex;
  const auto counted_with = [&](bool busy) {
    CountedRtViolations counting;
    std::thread other([&] {
      if (!busy) return;
      const std::lock_guard<std::mutex> guard(mutex);
      for (int i = 0; i < 10; ++i) {
        int* volatile p = new int(i);
        delete p;
      }
    });
    other.join();
    return counting.stop();
  };
  counted_with(false);  // the first thread of a process also sets up glibc's stack cache
  const RtViolations idle = counted_with(false);
  const RtViolations busy = counted_with(true);
  EXPECT_EQ(busy.locks, idle.locks);
  EXPECT_EQ(busy.allocations, idle.allocations);
}

TEST(ServoNoAllocation, StoppingOnAFaultDoesNotAllocateEither) {
  // The fault paths are part of the tick too: a NaN force stops the run on its first tick.
  const auto program = program_of({grating(0.003, 0.0, {std::nanf(""), 1.0f})});
  PatchEvaluator evaluator(program);
  SimJoystick joystick(sim_device_limits(), HandScript{}, 10);
  VirtualClock clock;
  ServoConfig config;
  config.duration_s = 0.01;
  std::size_t count = 0;
  std::string stop_reason;
  {
    CountedAllocations counting;
    const ServoReport report = run_servo_loop(joystick, evaluator, clock, config);
    count = counting.stop();
    stop_reason = report.stop_reason;
  }
  EXPECT_EQ(stop_reason, "non-finite force");
  EXPECT_LE(count, 3u);  // the two timing histograms and the report's stop_reason text, after the loop
}

}  // namespace
}  // namespace sandpaper::runtime
