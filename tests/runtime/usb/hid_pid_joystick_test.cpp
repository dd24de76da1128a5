// The HID PID driver through the fake transport: every byte it sends at open, per tick and at
// shutdown; position decoding; unplug and read timeout mid-run stop the servo loop with zero force;
// no allocation in the _rt calls.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <memory>
#include <string>
#include <thread>

#include "allocation_counter.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/runtime/usb/hid_pid_joystick.hpp"
#include "usb_test_support.hpp"

namespace sandpaper::runtime::usb {
namespace {

using testing::FakeTransport;
using testing::Op;
using Bytes = std::vector<std::uint8_t>;

struct Step {
  Op op;
  Bytes bytes;
};

std::vector<Step> steps(const FakeTransport& t, std::size_t from = 0) {
  std::vector<Step> out;
  for (std::size_t i = from; i < t.log().size(); ++i) out.push_back({t.log()[i].op, t.log()[i].data()});
  return out;
}

void expect_steps(const std::vector<Step>& got, const std::vector<Step>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    SCOPED_TRACE(::testing::Message() << "transfer " << i);
    EXPECT_EQ(static_cast<int>(got[i].op), static_cast<int>(want[i].op));
    EXPECT_EQ(got[i].bytes, want[i].bytes);
  }
}

// Set Effect (report 1): block, type 1 (Constant Force), duration 0xFFFF (infinite), trigger repeat,
// sample period and start delay 0, gain 255, trigger button 0 (none), axes enable with Direction
// Enable (0x04), and one polar direction in ordinal 1 (0..36000 hundredths of a degree): the X
// effect at 90 degrees (9000, 0x2328), the Y effect at 180 (18000, 0x4650), as hid-pidff sends them.
Bytes set_effect(std::uint8_t block, std::uint8_t axes) {
  const std::uint8_t lo = axes == 0x01 ? 0x28 : 0x50, hi = axes == 0x01 ? 0x23 : 0x46;
  return {0x01, block, 0x01, 0xFF, 0xFF, 0, 0, 0, 0, 0, 0, 0xFF, 0x00, static_cast<std::uint8_t>(axes | 0x04), lo, hi, 0, 0};
}

const std::vector<Step> kOpen = {
    {Op::Detach, {}},
    {Op::Claim, {}},
    {Op::Descriptor, {}},
    {Op::GetFeature, {0x13}},              // PID Pool
    {Op::Output, {0x0C, 0x04}},            // Device Control: Reset
    {Op::Output, {0x0C, 0x01}},            // Device Control: Enable Actuators
    {Op::SetFeature, {0x11, 0x01, 0, 0}},  // Create New Effect: Constant Force, byte count 0
    {Op::GetFeature, {0x12}},              // Block Load -> block 1
    {Op::Output, set_effect(1, 0x01)},     // Set Effect on X
    {Op::Output, {0x05, 0x01, 0, 0}},      // Set Constant Force 0
    {Op::Output, {0x0A, 0x01, 0x01, 0x01}},  // Effect Operation: start, loop count 1
    {Op::SetFeature, {0x11, 0x01, 0, 0}},
    {Op::GetFeature, {0x12}},              // -> block 2
    {Op::Output, set_effect(2, 0x02)},     // Set Effect on Y
    {Op::Output, {0x05, 0x02, 0, 0}},
    {Op::Output, {0x0A, 0x02, 0x01, 0x01}},
};

const std::vector<Step> kShutdown = {
    {Op::Output, {0x05, 0x01, 0, 0}},        // zero force
    {Op::Output, {0x05, 0x02, 0, 0}},
    {Op::Output, {0x0A, 0x01, 0x03, 0x00}},  // Effect Operation: stop
    {Op::Output, {0x0A, 0x02, 0x03, 0x00}},
    {Op::Output, {0x0B, 0x01}},              // Block Free
    {Op::Output, {0x0B, 0x02}},
    {Op::Output, {0x0C, 0x03}},              // Device Control: Stop All Effects
    {Op::Output, {0x0C, 0x02}},              // Device Control: Disable Actuators
    {Op::Release, {}},
    {Op::Attach, {}},                        // the kernel's HID driver gets the device back
};

TEST(HidPidJoystick, OpenSendsTheEffectCreationSequence) {
  auto t = testing::primed_transport();
  HidPidJoystick joystick(*t, testing::openffboard(), testing::synchronous());
  expect_steps(steps(*t), kOpen);
  EXPECT_EQ(joystick.effect_block_index(0), 1);
  EXPECT_EQ(joystick.effect_block_index(1), 2);
  EXPECT_FALSE(t->kernel_driver_attached());
  EXPECT_TRUE(t->claimed());
  EXPECT_EQ(joystick.limits().name, "openffboard-2axis");
}

TEST(HidPidJoystick, EachTickSendsSetConstantForcePerAxisScaledSignedAndClamped) {
  auto t = testing::primed_transport();
  HidPidJoystick joystick(*t, testing::openffboard(), testing::synchronous());
  const std::size_t start = t->log().size();
  // 1 mN per command unit (testing::openffboard()) and command_sense -1 on both axes (as
  // openffboard-2axis.toml: a positive magnitude pushes the OpenFFBoard's handle toward -x): 1.5 N -> -1500 = 0xFA24;
  // -2.25 N -> 2250 = 0x08CA.
  ASSERT_TRUE(joystick.write_force_rt({1.5, -2.25}));
  // Beyond the Magnitude field's logical range -10000..10000: clamped, sign kept.
  ASSERT_TRUE(joystick.write_force_rt({12.0, -20.0}));
  ASSERT_TRUE(joystick.write_force_rt({0.0004, -0.0006}));  // rounds to 0 and 1
  expect_steps(steps(*t, start), {{Op::Output, {0x05, 0x01, 0x24, 0xFA}},
                                  {Op::Output, {0x05, 0x02, 0xCA, 0x08}},
                                  {Op::Output, {0x05, 0x01, 0xF0, 0xD8}},
                                  {Op::Output, {0x05, 0x02, 0x10, 0x27}},
                                  {Op::Output, {0x05, 0x01, 0x00, 0x00}},
                                  {Op::Output, {0x05, 0x02, 0x01, 0x00}}});
}

TEST(HidPidJoystick, ADeviceWhosePositiveCommandPushesTowardPlusGetsTheForceUnsigned) {
  calibration::DeviceCalibration plus = testing::openffboard();
  plus.axis[0].command_sense = 1;
  plus.axis[1].command_sense = 1;
  auto t = testing::primed_transport();
  HidPidJoystick joystick(*t, plus, testing::synchronous());
  const std::size_t start = t->log().size();
  ASSERT_TRUE(joystick.write_force_rt({1.5, -2.25}));  // 1500 = 0x05DC; -2250 = 0xF736
  expect_steps(steps(*t, start), {{Op::Output, {0x05, 0x01, 0xDC, 0x05}}, {Op::Output, {0x05, 0x02, 0x36, 0xF7}}});
}

TEST(HidPidJoystick, CloseSendsTheShutdownSequenceAndGivesTheDeviceBack) {
  auto t = testing::primed_transport();
  std::size_t start = 0;
  {
    HidPidJoystick joystick(*t, testing::openffboard(), testing::synchronous());
    ASSERT_TRUE(joystick.write_force_rt({1.0, 1.0}));
    start = t->log().size();
  }  // the destructor closes
  expect_steps(steps(*t, start), kShutdown);
  EXPECT_TRUE(t->kernel_driver_attached());
  EXPECT_FALSE(t->claimed());
}

// A busy firmware NAKs reports of the shutdown too (seen in the USB lab after Ctrl-C): each is
// sent again, so the device still ends with zero force, its effects freed and its actuators off.
TEST(HidPidJoystick, AShutdownReportTheDeviceNaksIsSentAgain) {
  auto t = testing::primed_transport();
  std::size_t start = 0;
  {
    HidPidJoystick joystick(*t, testing::openffboard(), testing::synchronous());
    ASSERT_TRUE(joystick.write_force_rt({1.0, 1.0}));
    start = t->log().size();
    t->time_out_outputs(4);
  }
  expect_steps(steps(*t, start), kShutdown);
}

// ... within close_timeout_ms: a device that takes nothing does not hold the program.
TEST(HidPidJoystick, AShutdownThatKeepsTimingOutEndsWithinItsLimit) {
  auto t = testing::primed_transport();
  HidPidOptions options = testing::synchronous();
  options.close_timeout_ms = 30;
  HidPidJoystick joystick(*t, testing::openffboard(), options);
  const std::size_t start = t->log().size();
  t->time_out_outputs(std::numeric_limits<std::size_t>::max());
  joystick.close();
  const auto got = steps(*t, start);
  ASSERT_EQ(got.size(), 2u);  // nothing reached the device but the interface was given back
  EXPECT_EQ(static_cast<int>(got[0].op), static_cast<int>(Op::Release));
  EXPECT_EQ(static_cast<int>(got[1].op), static_cast<int>(Op::Attach));
}

TEST(HidPidJoystick, InputReportsDecodeToMetresOverTheCalibratedWorkspace) {
  auto t = testing::primed_transport();
  // A PID State report (ID 2) first: skipped. Then X = 16384, Y = -32767 of -32767..32767 over the
  // calibration's 100 mm x 100 mm: x = 16384 / 32767 * 50 mm, y = -50 mm.
  t->add_input({UsbStatus::Ok, {0x02, 0x03, 0x02}});
  t->add_input({UsbStatus::Ok, testing::position_report(16384, -32767)});
  HidPidJoystick joystick(*t, testing::openffboard(), testing::synchronous());
  glm::dvec2 p{9, 9};
  ASSERT_TRUE(joystick.read_position_rt(0.0, p));
  EXPECT_NEAR(p.x, 16384.0 / 32767.0 * 0.05, 1e-12);
  EXPECT_NEAR(p.y, -0.05, 1e-12);
  EXPECT_EQ(joystick.fault(), DeviceFault::None);
  EXPECT_TRUE(joystick.position_fresh_rt());
  // No report at the next tick: the same position, held, and said not to be fresh (the servo loop
  // differentiates only between fresh ones); then a new report is.
  ASSERT_TRUE(joystick.read_position_rt(0.001, p));
  EXPECT_FALSE(joystick.position_fresh_rt());
  EXPECT_NEAR(p.x, 16384.0 / 32767.0 * 0.05, 1e-12);
  t->add_input({UsbStatus::Ok, testing::position_report(0, 0)});
  ASSERT_TRUE(joystick.read_position_rt(0.002, p));
  EXPECT_TRUE(joystick.position_fresh_rt());
  EXPECT_NEAR(p.x, 0.0, 1e-12);
}

TEST(HidPidJoystick, OpenFailsCleanlyWhenTheDeviceHasNoRoomAndGivesItBack) {
  auto t = std::make_unique<FakeTransport>(testing::test_descriptor());
  t->add_feature_reply(0x13, {0x13, 0x00, 0x10, 0x04, 0x01});
  t->add_feature_reply(0x12, {0x12, 0x00, 0x02, 0x00, 0x00});  // Block Load: full
  try {
    HidPidJoystick joystick(*t, testing::openffboard(), testing::synchronous());
    FAIL() << "opened a device whose effect memory is full";
  } catch (const HidPidError& e) {
    EXPECT_NE(std::string(e.what()).find("full"), std::string::npos) << e.what();
  }
  const auto got = steps(*t);
  ASSERT_GE(got.size(), 4u);
  // Stop all, disable actuators, release, reattach.
  EXPECT_EQ(got[got.size() - 4].bytes, (Bytes{0x0C, 0x03}));
  EXPECT_EQ(got[got.size() - 3].bytes, (Bytes{0x0C, 0x02}));
  EXPECT_EQ(static_cast<int>(got[got.size() - 2].op), static_cast<int>(Op::Release));
  EXPECT_EQ(static_cast<int>(got.back().op), static_cast<int>(Op::Attach));
  EXPECT_TRUE(t->kernel_driver_attached());
}

// A busy firmware NAKs an output report past the transport's short timeout (seen in the USB lab
// under load, on Device Control): the open sequence sends it again, and the device sees each once.
TEST(HidPidJoystick, AnOpenReportTheDeviceNaksPastTheTimeoutIsSentAgain) {
  auto t = testing::primed_transport();
  t->time_out_outputs(5);
  HidPidJoystick joystick(*t, testing::openffboard(), testing::synchronous());
  expect_steps(steps(*t), kOpen);
}

// ... until open_write_timeout_ms: then the open fails, naming the step and the report's HID usage,
// and gives the device back.
TEST(HidPidJoystick, AnOpenReportThatKeepsTimingOutFailsNamingTheStep) {
  auto t = testing::primed_transport();
  t->time_out_outputs(std::numeric_limits<std::size_t>::max());
  HidPidOptions options = testing::synchronous();
  options.open_write_timeout_ms = 20;
  try {
    HidPidJoystick joystick(*t, testing::openffboard(), options);
    FAIL() << "opened a device that takes no output report";
  } catch (const HidPidError& e) {
    EXPECT_EQ(e.status, UsbStatus::Timeout);
    EXPECT_EQ(std::string(e.what()),
              "Device Control (Device Reset) failed: timed out (Output report 0x0C, HID page 0x000F usage 0x0096) "
              "after 20 ms of retries");
  }
  EXPECT_TRUE(t->kernel_driver_attached());
  EXPECT_FALSE(t->claimed());
}

// A Feature report the device stalls (no Block Load reply): the error names the step and the usage.
TEST(HidPidJoystick, AFeatureReportStalledInTheOpenNamesTheStepAndItsUsage) {
  auto t = std::make_unique<FakeTransport>(testing::test_descriptor());
  t->add_feature_reply(0x13, {0x13, 0x00, 0x10, 0x04, 0x01});
  try {
    HidPidJoystick joystick(*t, testing::openffboard(), testing::synchronous());
    FAIL() << "opened a device that stalls Block Load";
  } catch (const HidPidError& e) {
    EXPECT_EQ(e.status, UsbStatus::Stalled);
    EXPECT_EQ(std::string(e.what()),
              "Block Load failed: stalled (the device refused the request) (Feature report 0x12, HID page 0x000F usage 0x0089)");
  }
  EXPECT_TRUE(t->kernel_driver_attached());
}

// The hand-written descriptor with `from` (its first occurrence) replaced by `to`.
Bytes edited_descriptor(const Bytes& from, const Bytes& to) {
  Bytes d = testing::test_descriptor();
  const auto at = std::search(d.begin(), d.end(), from.begin(), from.end());
  EXPECT_NE(at, d.end());
  const auto i = at - d.begin();
  d.erase(d.begin() + i, d.begin() + i + static_cast<std::ptrdiff_t>(from.size()));
  d.insert(d.begin() + i, to.begin(), to.end());
  return d;
}

// The error opening a device with this descriptor gives, or "" if it opens.
std::string open_error(const Bytes& descriptor, FakeTransport** kept = nullptr) {
  static std::unique_ptr<FakeTransport> t;
  t = std::make_unique<FakeTransport>(descriptor);
  t->add_feature_reply(0x13, {0x13, 0x00, 0x10, 0x04, 0x01});
  t->add_feature_reply(0x12, {0x12, 0x01, 0x01, 0x27, 0x00});
  t->add_feature_reply(0x12, {0x12, 0x02, 0x01, 0x26, 0x00});
  t->add_input({UsbStatus::Ok, testing::position_report(0, 0)});
  if (kept) *kept = t.get();
  try {
    HidPidJoystick joystick(*t, testing::openffboard(), testing::synchronous());
    return "";
  } catch (const HidPidError& e) {
    return e.what();
  }
}

// Every report is built in a 64-byte buffer, and only the position and Set Constant Force reports
// were checked against it: a descriptor with a longer Set Effect (or Effect Operation, Block Free,
// Device Control, Create New Effect) report made the driver hand over bytes past the buffer
// (docs/RELIABILITY.md, F23). Such a device is refused, with the report named, before any is sent.
TEST(HidPidJoystick, ADescriptorWithAReportLongerThanThePacketIsRefusedBeforeAnyTransferReadsPastIt) {
  // Eighty bytes of constant padding at the end of Set Effect (output report 1): 98 bytes.
  const Bytes end_of_set_effect = {0x55, 0x00, 0x66, 0x00, 0x00, 0xC0, 0xC0};
  const Bytes padded = {0x55, 0x00, 0x66, 0x00, 0x00, 0xC0, 0x75, 0x08, 0x95, 0x50, 0x91, 0x03, 0xC0};
  FakeTransport* t = nullptr;
  const std::string error = open_error(edited_descriptor(end_of_set_effect, padded), &t);
  EXPECT_NE(error.find("Set Effect report (ID 1) is 98 bytes; the driver sends and reads reports of at most 64"),
            std::string::npos) << error;
  EXPECT_LE(t->longest_transfer(), 64u);
  EXPECT_TRUE(t->kernel_driver_attached());
  // The same padding on the position report is refused as before, now by name.
  const Bytes position_axes = {0x75, 0x10, 0x95, 0x02, 0x81, 0x02};
  const std::string input = open_error(edited_descriptor(position_axes, {0x75, 0x10, 0x95, 0x02, 0x81, 0x02, 0x75, 0x08, 0x95, 0x50, 0x81, 0x03}));
  EXPECT_NE(input.find("position (X, Y) report (ID 1) is 86 bytes"), std::string::npos) << input;
  EXPECT_EQ(open_error(testing::test_descriptor()), "");
}

// A Magnitude range without negative values (1..10000) cannot carry zero force: the tick's zero
// would have been sent as 1, and with a calibrated command limit below the range's minimum the
// clamp's bounds crossed (std::clamp's precondition; docs/RELIABILITY.md, F24). Refused at open.
TEST(HidPidJoystick, AMagnitudeRangeWithoutZeroInsideIsRefusedAtOpen) {
  const Bytes magnitude = {0x09, 0x70, 0x16, 0xF0, 0xD8, 0x26, 0x10, 0x27};  // -10000..10000
  const std::string error = open_error(edited_descriptor(magnitude, {0x09, 0x70, 0x15, 0x01, 0x26, 0x10, 0x27}));
  EXPECT_NE(error.find("Magnitude (Set Constant Force) has the logical range 1..10000; the driver needs one with negative"),
            std::string::npos) << error;
  // An axis whose range is one value carries no position: refused too, not read as a joystick stuck at 0.
  const Bytes axes_range = {0x16, 0x01, 0x80, 0x26, 0xFF, 0x7F};  // -32767..32767
  const std::string flat = open_error(edited_descriptor(axes_range, {0x15, 0x05, 0x25, 0x05}));
  EXPECT_NE(flat.find("usage 0x0030 (position) has the logical range 5..5, which carries no position"), std::string::npos) << flat;
}

// A force source that always asks for the same force.
class ConstantForce final : public ForceSource {
 public:
  explicit ConstantForce(glm::dvec2 f) : f_(f) {}
  glm::dvec2 force_rt(const HandState&, double) noexcept override { return f_; }
  void reset_rt(const HandState&) noexcept override {}

 private:
  glm::dvec2 f_;
};

// A force that rises by 1 N/s on both axes: a new command unit (1 mN) every 1 ms tick.
class RisingForce final : public ForceSource {
 public:
  glm::dvec2 force_rt(const HandState&, double dt_s) noexcept override {
    t_s_ += dt_s;
    return {0.5 + t_s_, 0.5 + t_s_};
  }
  void reset_rt(const HandState&) noexcept override { t_s_ = 0; }

 private:
  double t_s_ = 0;
};

ServoConfig config(double duration_s) {
  ServoConfig c;
  c.rate_hz = 1000;
  c.duration_s = duration_s;
  c.ramp_s = 0;  // the bytes below are the full force from the first tick
  return c;
}

TEST(HidPidJoystick, UnplugMidRunStopsTheLoopAndNamesTheCause) {
  auto t = testing::primed_transport();
  for (int k = 0; k < 100; ++k) t->add_input({UsbStatus::Ok, testing::position_report(0, 0)});
  HidPidJoystick joystick(*t, testing::openffboard(), testing::synchronous());
  t->unplug_after_outputs(2 * 10);  // ten ticks of two Set Constant Force reports, then gone
  ConstantForce source({1.0, 0.5});
  VirtualClock clock;
  const ServoReport report = run_servo_loop(joystick, source, clock, config(0.1));
  EXPECT_EQ(report.ticks, 11u);
  EXPECT_EQ(report.stop_cause, StopCause::DeviceUnplugged);  // named through last_fault_rt()
  EXPECT_STREQ(stop_cause_name(report.stop_cause), "device_unplugged");
  EXPECT_EQ(joystick.fault(), DeviceFault::Unplugged);
  EXPECT_EQ(joystick.fault_status(), UsbStatus::NoDevice);
  EXPECT_STREQ(to_string(joystick.fault()), "device unplugged");
  // Nothing after the unplug reached the device; the last thing it got was the 10th tick's force
  // (y 0.5 N: -500 = 0xFE0C with command_sense -1).
  const auto got = steps(*t);
  EXPECT_EQ(got.back().bytes, (Bytes{0x05, 0x02, 0x0C, 0xFE}));
}

TEST(HidPidJoystick, ReadTimeoutStopsTheLoopWithZeroForceSent) {
  auto t = testing::primed_transport();
  for (int k = 0; k < 5; ++k) t->add_input({UsbStatus::Ok, testing::position_report(100, 100)});
  // Then no more reports: every read times out.
  HidPidOptions options = testing::synchronous();
  options.stale_limit_s = 0.0025;  // stale after 2.5 ms without a report
  HidPidJoystick joystick(*t, testing::openffboard(), options);
  ConstantForce source({1.0, 0.5});
  VirtualClock clock;
  const std::size_t start = t->log().size();
  const ServoReport report = run_servo_loop(joystick, source, clock, config(0.1));
  EXPECT_EQ(report.stop_cause, StopCause::DeviceReadTimeout);
  EXPECT_EQ(joystick.fault(), DeviceFault::ReadTimedOut);
  EXPECT_EQ(report.ticks, 5u + 3u);  // 5 fresh ticks, 2 within the limit, the 3rd stale (t - last > 2.5 ms)
  const auto got = steps(*t, start);
  ASSERT_GE(got.size(), 2u);
  // The last two transfers are the zero force on both axes, sent when the read failed.
  EXPECT_EQ(got[got.size() - 2].bytes, (Bytes{0x05, 0x01, 0x00, 0x00}));
  EXPECT_EQ(got.back().bytes, (Bytes{0x05, 0x02, 0x00, 0x00}));
}

// The OpenFFBoard resends an unchanged position only every 101 ms (openffboard-2axis.toml [usb]
// idle_report_period): a handle held still must not trip the watchdog, which then waits twice that.
TEST(HidPidJoystick, AHandleHeldStillIsNotADeviceGoneQuiet) {
  auto t = testing::primed_transport();
  for (int k = 0; k < 5; ++k) t->add_input({UsbStatus::Ok, testing::position_report(100, 100)});
  HidPidJoystick joystick(*t, testing::openffboard(), testing::synchronous());
  ConstantForce source({1.0, 0.5});
  VirtualClock clock;
  const ServoReport report = run_servo_loop(joystick, source, clock, config(0.5));
  EXPECT_EQ(report.stop_cause, StopCause::DeviceReadTimeout);
  // 5 fresh ticks, then stale after 202 ms (2 x 101 ms) of 1 ms ticks; 50 ms would stop at 5 + 51.
  EXPECT_NEAR(static_cast<double>(report.ticks), 5.0 + 203.0, 1.0);
}

TEST(HidPidJoystick, ReadErrorOtherThanTimeoutStopsAtOnce) {
  auto t = testing::primed_transport();
  t->add_input({UsbStatus::Ok, testing::position_report(0, 0)});
  t->add_input({UsbStatus::Other, {}});
  HidPidJoystick joystick(*t, testing::openffboard(), testing::synchronous());
  ConstantForce source({0.0, 0.0});
  VirtualClock clock;
  const ServoReport report = run_servo_loop(joystick, source, clock, config(0.1));
  EXPECT_EQ(report.ticks, 2u);
  EXPECT_EQ(report.stop_cause, StopCause::DeviceReadFailed);
  EXPECT_EQ(joystick.fault(), DeviceFault::ReadFailed);
}

TEST(HidPidJoystick, TicksDoNotAllocate) {
  auto t = testing::primed_transport();
  for (int k = 0; k < 1000; ++k) {
    t->add_input({UsbStatus::Ok, {0x02, 0x00, 0x00}});
    t->add_input({UsbStatus::Ok, testing::position_report(static_cast<std::int16_t>(k), static_cast<std::int16_t>(-k))});
  }
  HidPidJoystick joystick(*t, testing::openffboard(), testing::synchronous());
  glm::dvec2 p{0, 0};
  bool ok = true;
  std::size_t count = 0;
  {
    sandpaper::test::CountedAllocations counting;
    for (int k = 0; k < 1000; ++k) {
      ok = joystick.read_position_rt(k * 1e-3, p) && ok;
      ok = joystick.write_force_rt({k * 1e-3, -k * 1e-3}) && ok;
    }
    count = counting.stop();
  }
  EXPECT_TRUE(ok);
  EXPECT_EQ(count, 0u);
  EXPECT_EQ(joystick.last_command()[0], -999);  // 0.999 N with command_sense -1
}

// The default: transfers on the driver's own I/O thread, the tick only exchanging atomics with it.

// A device streaming position reports (the last one repeats, as a joystick at rest reports).
std::unique_ptr<testing::FakeTransport> streaming_transport() {
  auto t = testing::primed_transport();
  t->add_input({UsbStatus::Ok, testing::position_report(16384, -32767)});
  t->repeat_last_input = true;
  t->inputs_arrived = true;
  return t;
}

TEST(HidPidJoystickIoThread, TheTickPublishesAndTheIoThreadSends) {
  auto t = streaming_transport();
  HidPidJoystick joystick(*t, testing::openffboard());
  t->watch_thread(std::this_thread::get_id());  // this thread plays the servo tick
  const std::size_t start = t->log().size();
  glm::dvec2 p{0, 0};
  ASSERT_TRUE(joystick.flush_nonrt(30.0));  // the I/O thread has read past the queued report
  ASSERT_TRUE(joystick.read_position_rt(0.0, p));
  EXPECT_NEAR(p.x, 16384.0 / 32767.0 * 0.05, 1e-7);
  EXPECT_NEAR(p.y, -0.05, 1e-7);
  ASSERT_TRUE(joystick.write_force_rt({1.5, -2.25}));
  ASSERT_TRUE(joystick.flush_nonrt(30.0));
  EXPECT_EQ(t->transfers_on_watched_thread(), 0u);  // the tick made no transfer itself
  // The same bytes as the synchronous driver sends for the same force (command_sense -1).
  const auto got = steps(*t, start);
  ASSERT_GE(got.size(), 2u);
  EXPECT_EQ(got[got.size() - 2].bytes, (Bytes{0x05, 0x01, 0x24, 0xFA}));
  EXPECT_EQ(got.back().bytes, (Bytes{0x05, 0x02, 0xCA, 0x08}));
  EXPECT_EQ(joystick.last_command()[0], -1500);
}

// A full-speed interrupt OUT endpoint moves one report per 1 ms frame: an axis whose magnitude has
// not changed is not sent again, so a texture scanned along X gets every frame.
TEST(HidPidJoystickIoThread, OnlyAnAxisWhoseForceChangedIsSent) {
  auto t = streaming_transport();
  HidPidJoystick joystick(*t, testing::openffboard());
  ASSERT_TRUE(joystick.flush_nonrt(30.0));
  const std::size_t start = t->log().size();
  ASSERT_TRUE(joystick.write_force_rt({1.5, 0.0}));  // Y stays at the zero the open sent
  ASSERT_TRUE(joystick.flush_nonrt(30.0));
  ASSERT_TRUE(joystick.write_force_rt({1.5, -2.25}));  // now only Y changes
  ASSERT_TRUE(joystick.flush_nonrt(30.0));
  expect_steps(steps(*t, start), {{Op::Output, {0x05, 0x01, 0x24, 0xFA}}, {Op::Output, {0x05, 0x02, 0xCA, 0x08}}});
}

// A Set Constant Force the device NAKs past the transfer's timeout (seen in the USB lab, where the
// firmware re-arms its OUT endpoint only after taking the last report) is sent again, not a fault.
TEST(HidPidJoystickIoThread, AForceTransferThatTimesOutIsSentAgain) {
  auto t = streaming_transport();
  HidPidJoystick joystick(*t, testing::openffboard());
  ASSERT_TRUE(joystick.flush_nonrt(30.0));
  t->time_out_outputs(3);
  const std::size_t start = t->log().size();
  ASSERT_TRUE(joystick.write_force_rt({1.5, -2.25}));
  ASSERT_TRUE(joystick.flush_nonrt(30.0));  // sent in the end
  EXPECT_EQ(joystick.fault(), DeviceFault::None);
  // Each axis's report reached the device once (the one that got through first is not sent again).
  expect_steps(steps(*t, start), {{Op::Output, {0x05, 0x02, 0xCA, 0x08}}, {Op::Output, {0x05, 0x01, 0x24, 0xFA}}});
}

// ... but a device that takes no force at all for the watchdog's time has gone quiet.
TEST(HidPidJoystickIoThread, ForceTransfersTimingOutPastTheWatchdogStopTheLoop) {
  auto t = streaming_transport();
  HidPidOptions options;
  options.stale_limit_s = 0.05;
  HidPidJoystick joystick(*t, testing::openffboard(), options);
  ASSERT_TRUE(joystick.flush_nonrt(30.0));
  t->time_out_outputs(std::numeric_limits<std::size_t>::max());
  ConstantForce source({1.0, 0.5});
  ServoConfig c = config(10.0);
  c.deadline_guard_periods = 1e6;  // a loaded test machine must not stop it first
  ServoThread servo;
  servo.start_nonrt(joystick, source, c);
  const ServoReport report = servo.join_nonrt();
  EXPECT_EQ(report.stop_cause, StopCause::DeviceWriteFailed);
  EXPECT_EQ(joystick.fault(), DeviceFault::WriteFailed);
  EXPECT_LT(report.ticks, 10'000u);
}

TEST(HidPidJoystickIoThread, ATransferThatNeverCompletesDoesNotHoldTheTick) {
  auto t = streaming_transport();
  HidPidOptions options;
  options.stale_limit_s = 0.05;
  HidPidJoystick joystick(*t, testing::openffboard(), options);
  ASSERT_TRUE(joystick.flush_nonrt(30.0));
  t->hang_outputs();  // the next Set Constant Force never completes (until released below)
  // The servo loop on its real-time thread, 10 s long: only the watchdog can end it early.
  ConstantForce source({1.0, 0.5});
  ServoConfig c = config(10.0);
  c.deadline_guard_periods = 1e6;  // a loaded test machine must not stop it first: the watchdog is under test
  ServoThread servo;
  struct Watching final : ForceSource {
    ForceSource& inner;
    std::atomic<std::thread::id>& id;
    Watching(ForceSource& s, std::atomic<std::thread::id>& i) : inner(s), id(i) {}
    glm::dvec2 force_rt(const HandState& h, double dt) noexcept override {
      id.store(std::this_thread::get_id());
      return inner.force_rt(h, dt);
    }
    void reset_rt(const HandState& h) noexcept override { inner.reset_rt(h); }
  };
  std::atomic<std::thread::id> tick_thread{};
  Watching watching(source, tick_thread);
  servo.start_nonrt(joystick, watching, c);
  while (tick_thread.load() == std::thread::id{} && !servo.finished()) std::this_thread::yield();
  t->watch_thread(tick_thread.load());
  const ServoReport report = servo.join_nonrt();  // returns although the I/O thread is still stuck
  EXPECT_EQ(t->hung_outputs(), 1u);
  EXPECT_EQ(report.stop_cause, StopCause::DeviceReadTimeout);
  EXPECT_LT(report.ticks, 10'000u);
  EXPECT_EQ(t->transfers_on_watched_thread(), 0u);
  // Once the stuck transfer completes (it carried the old force), the shutdown sends zero on both
  // axes before stopping the effects.
  const std::size_t start = t->log().size();
  t->release_outputs();
  joystick.close();
  const auto got = steps(*t, start);
  const auto stop = std::find_if(got.begin(), got.end(), [](const Step& s) { return s.bytes == Bytes{0x0A, 0x01, 0x03, 0x00}; });
  ASSERT_NE(stop, got.end());
  ASSERT_GE(stop - got.begin(), 2);
  EXPECT_EQ((stop - 2)->bytes, (Bytes{0x05, 0x01, 0x00, 0x00}));
  EXPECT_EQ((stop - 1)->bytes, (Bytes{0x05, 0x02, 0x00, 0x00}));
}

TEST(HidPidJoystickIoThread, UnplugMidRunStopsTheLoopWithTheCauseNamed) {
  auto t = streaming_transport();
  HidPidOptions options;
  options.stale_limit_s = 5.0;  // a loaded machine may starve the I/O thread for a while: only the unplug may end this run
  HidPidJoystick joystick(*t, testing::openffboard(), options);
  ASSERT_TRUE(joystick.flush_nonrt(30.0));
  t->unplug_after_outputs(20);  // ten forces sent, then the device is gone
  RisingForce source;  // a new magnitude every tick, so sent every I/O cycle
  ServoConfig c = config(10.0);
  c.deadline_guard_periods = 1e6;
  const ServoReport report = run_servo_thread_nonrt(joystick, source, c);
  EXPECT_EQ(report.stop_cause, StopCause::DeviceUnplugged);
  EXPECT_EQ(joystick.fault(), DeviceFault::Unplugged);
  EXPECT_LT(report.ticks, 10'000u);
}

TEST(HidPidJoystickIoThread, TicksNeitherAllocateNorLock) {
  auto t = streaming_transport();
  HidPidJoystick joystick(*t, testing::openffboard());
  ASSERT_TRUE(joystick.flush_nonrt(30.0));
  glm::dvec2 p{0, 0};
  bool ok = true;
  sandpaper::test::RtViolations seen;
  {
    sandpaper::test::CountedRtViolations counting;
    for (int k = 0; k < 1000; ++k) {
      ok = joystick.read_position_rt(k * 1e-5, p) && ok;  // 10 ms of servo time: never stale
      ok = joystick.write_force_rt({k * 1e-3, -k * 1e-3}) && ok;
    }
    seen = counting.stop();
  }
  EXPECT_TRUE(ok);
  EXPECT_EQ(seen.allocations, 0u);
  EXPECT_EQ(seen.locks, 0u);
  ASSERT_TRUE(joystick.flush_nonrt(30.0));
  EXPECT_EQ(joystick.last_command()[0], -999);  // the I/O thread sent the latest force (command_sense -1)
}

}  // namespace
}  // namespace sandpaper::runtime::usb
