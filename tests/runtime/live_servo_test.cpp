// The one live-servo host (runtime/live_servo.hpp): what a device says of itself reaches every run
// it hosts (its table sampling, its command steps, whether it can follow simulated time), and a run
// on a thread of its own starts, stops and is joined once.
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <memory>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include "runtime_test_support.hpp"
#include "sandpaper/runtime/live_servo.hpp"

using namespace sandpaper::runtime;
using namespace sandpaper::runtime::testing;

namespace {

// A handle held still at `at`, describing itself as told; records the last force written.
class StillDevice final : public Device {
 public:
  StillDevice(glm::dvec2 at, TableSampling tables, CommandQuantum quantum = {}, bool virtual_ok = true)
      : at_(at), tables_(tables), quantum_(quantum), virtual_ok_(virtual_ok) {
    limits_.name = "still";
  }
  const DeviceLimits& limits() const noexcept override { return limits_; }
  CommandQuantum command_quantum() const noexcept override { return quantum_; }
  TableSampling table_sampling() const noexcept override { return tables_; }
  bool follows_virtual_clock() const noexcept override { return virtual_ok_; }
  bool read_position_rt(double, glm::dvec2& p) noexcept override {
    p = at_;
    return true;
  }
  bool write_force_rt(glm::dvec2 f) noexcept override {
    if (f != glm::dvec2{0, 0}) last_nonzero = f;
    return true;
  }
  glm::dvec2 last_nonzero{0, 0};

 private:
  DeviceLimits limits_;
  glm::dvec2 at_;
  TableSampling tables_;
  CommandQuantum quantum_;
  bool virtual_ok_;
};

ServoConfig short_run() {
  ServoConfig c;
  c.rate_hz = 1000;
  c.duration_s = 0.02;
  c.ramp_s = 0;
  return c;
}

// A 4-sample grating of period 4 mm (0, 1, 2, 3 N); the hand 1.4 samples in.
const auto kProgram = std::make_shared<const sandpaper::schema::PatchProgram>(program_of({grating(0.004, 0, {0.0f, 1.0f, 2.0f, 3.0f})}));
const glm::dvec2 kAt{0.0014, 0};

}  // namespace

TEST(LiveServo, SourcesReadTablesAsTheDeviceDoes) {
  // Held, the force is the nearest sample's (1 N); interpolated, 1.4 N (Appendix B 2.1).
  StillDevice held(kAt, TableSampling::Hold), smooth(kAt, TableSampling::Interpolate);
  for (StillDevice* d : {&held, &smooth}) {
    LiveServo host(*d, patch_source_for(*d, kProgram), {});
    ASSERT_EQ(host.run_virtual_nonrt(short_run()).stop_cause, StopCause::Completed);
  }
  EXPECT_DOUBLE_EQ(held.last_nonzero.x, 1.0);
  EXPECT_NEAR(smooth.last_nonzero.x, 1.4, 1e-6);
  // The host's own builder, for swaps, is the same.
  StillDevice held_again(kAt, TableSampling::Hold);
  LiveServo host(held_again, nullptr, {});
  host.offer_nonrt(host.patch_source_nonrt(kProgram));
  ASSERT_EQ(host.run_virtual_nonrt(short_run()).stop_cause, StopCause::Completed);
  EXPECT_DOUBLE_EQ(held_again.last_nonzero.x, 1.0);
}

TEST(LiveServo, TheLoopSendsTheDevicesCommandSteps) {
  // 0.3 N steps: 1.4 N is sent as 1.5 N, and the telemetry says so, though the config says nothing.
  CommandQuantum q;
  q.step_N[0] = q.step_N[1] = 0.3;
  StillDevice d(kAt, TableSampling::Interpolate, q);
  LiveServo::Options o;
  o.telemetry_records = 64;
  LiveServo host(d, patch_source_for(d, kProgram), o);
  ASSERT_EQ(host.run_virtual_nonrt(short_run()).stop_cause, StopCause::Completed);
  EXPECT_NEAR(d.last_nonzero.x, 1.5, 1e-12);
  TelemetryRecord r;
  int records = 0;
  while (host.telemetry()->pop_nonrt(r)) {
    ++records;
    EXPECT_NEAR(r.force_N.x, 1.5, 1e-12);
  }
  EXPECT_EQ(records, 20);
}

TEST(LiveServo, ADeviceAPersonMovesRefusesTheVirtualClock) {
  StillDevice held_by_hand(kAt, TableSampling::Interpolate, {}, /*virtual_ok=*/false);
  LiveServo host(held_by_hand, patch_source_for(held_by_hand, kProgram), {});
  EXPECT_THROW(host.run_virtual_nonrt(short_run()), std::invalid_argument);
}

TEST(LiveServo, ARunOnItsThreadStartsStopsAndJoinsOnce) {
  StillDevice d(kAt, TableSampling::Interpolate);
  LiveServo host(d, patch_source_for(d, kProgram), {});
  EXPECT_TRUE(host.finished());
  EXPECT_THROW(host.join_nonrt(), std::logic_error);
  ServoConfig until_stopped = short_run();
  until_stopped.duration_s = 0;  // the host's own stop flag makes this valid
  host.start_nonrt(until_stopped);
  EXPECT_TRUE(host.running());
  EXPECT_THROW(host.start_nonrt(until_stopped), std::logic_error);
  host.request_stop_nonrt();
  const ServoReport report = host.join_nonrt();
  EXPECT_EQ(report.stop_cause, StopCause::StopRequested);
  EXPECT_FALSE(host.running());
  // Started again, the stop asked for last time is forgotten: it plays until asked again.
  ServoConfig timed = short_run();
  host.start_nonrt(timed);
  EXPECT_EQ(host.join_nonrt().stop_cause, StopCause::Completed);
  EXPECT_NEAR(d.last_nonzero.x, 1.4, 1e-6);
}

namespace {

// A held device that is gone at its first read; `back` says whether the factory's check finds it at
// its port again. Counts how often it was given back and asked.
class VanishingDevice final : public HeldDevice {
 public:
  explicit VanishingDevice(bool gone) : gone_(gone) { limits_.name = "vanishing"; }
  const DeviceLimits& limits() const noexcept override { return limits_; }
  bool read_position_rt(double, glm::dvec2& p) noexcept override {
    p = {0, 0};
    return !gone_;
  }
  bool write_force_rt(glm::dvec2) noexcept override { return true; }
  DeviceFault last_fault_rt() const noexcept override { return DeviceFault::Unplugged; }
  void close_nonrt() noexcept override { ++closed; }
  std::string fault_detail_nonrt() const override { return gone_ ? "no device" : ""; }
  int closed = 0;

 private:
  DeviceLimits limits_;
  bool gone_;
};

}  // namespace

TEST(LiveServo, AnUnpluggedDeviceFoundBackIsAReset) {
  for (const bool back : {true, false}) {
    VanishingDevice d(/*gone=*/true);
    double asked_within_s = -1;
    d.watch_for_return_nonrt([&](double within_s) {
      asked_within_s = within_s;
      return back;
    });
    LiveServo host(d, patch_source_for(d, kProgram), {});
    host.start_nonrt(short_run());
    const ServoReport report = host.join_nonrt();
    EXPECT_EQ(report.stop_cause, back ? StopCause::DeviceReset : StopCause::DeviceUnplugged);
    EXPECT_EQ(report.stop_reason, stop_cause_text(report.stop_cause));
    EXPECT_DOUBLE_EQ(asked_within_s, kResetGraceS);
    EXPECT_GE(d.closed, 1);  // given back before its port is watched
  }
  // A run that ends well never asks, and a device nobody installed a check on is never found back.
  VanishingDevice present(/*gone=*/false);
  bool asked = false;
  present.watch_for_return_nonrt([&](double) { return asked = true; });
  LiveServo fine(present, patch_source_for(present, kProgram), {});
  fine.start_nonrt(short_run());
  EXPECT_EQ(fine.join_nonrt().stop_cause, StopCause::Completed);
  EXPECT_FALSE(asked);
  VanishingDevice unwatched(/*gone=*/true);
  LiveServo host(unwatched, patch_source_for(unwatched, kProgram), {});
  host.start_nonrt(short_run());
  EXPECT_EQ(host.join_nonrt().stop_cause, StopCause::DeviceUnplugged);
}

TEST(LiveServo, OffersGoOnWhileAnUnplugIsCheckedForAReset) {
  // The check waits (as a real one waits for the bus) until the test has offered a source from
  // another thread; an offer that waited for the check would leave it unanswered for 10 s.
  VanishingDevice d(/*gone=*/true);
  std::promise<void> checking, offered;
  auto offered_done = offered.get_future();
  bool offered_in_time = false;
  d.watch_for_return_nonrt([&](double) {
    checking.set_value();
    offered_in_time = offered_done.wait_for(std::chrono::seconds(10)) == std::future_status::ready;
    return true;
  });
  LiveServo host(d, patch_source_for(d, kProgram), {});
  host.start_nonrt(short_run());
  ServoReport report;
  std::thread joiner([&] { report = host.join_nonrt(); });
  checking.get_future().wait();
  host.offer_nonrt(patch_source_for(d, kProgram));
  host.collect_retired_nonrt();
  offered.set_value();
  joiner.join();
  EXPECT_TRUE(offered_in_time);
  EXPECT_EQ(report.stop_cause, StopCause::DeviceReset);
}
