// The USB lab's HID PID 1.0 device model (usb-lab/hid_pid) with the recorded SideWinder Force
// Feedback 2 descriptor behind it. The expected numbers come from the descriptor's items (the
// comments in tests/runtime/usb/data/ms_sidewinder_ffb2.hex) and from the PID class definition,
// worked out by hand here; the reports the tests send are built byte by byte from the same
// layout, not with the model's parser. Last, Sandpaper's own HID PID driver (runtime/usb) on the
// model, in one process.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "report_descriptor.hpp"
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/runtime/usb/hid_pid_joystick.hpp"
#include "sidewinder_ff2.hpp"

namespace sandpaper::usb_lab {
namespace {

using hid::ReportType;
using Bytes = std::vector<std::uint8_t>;

// ---- the parser on the FF2's descriptor ----

const hid::ReportField& field(const hid::ReportDescriptor& d, ReportType type, std::uint8_t id, std::uint32_t usage) {
  for (const hid::ReportField& f : d.fields)
    if (f.type == type && f.report_id == id && !f.constant &&
        (std::find(f.usages.begin(), f.usages.end(), usage) != f.usages.end() || f.innermost_collection() == usage))
      return f;
  throw std::runtime_error("no field with usage " + std::to_string(usage));
}

TEST(Ff2Descriptor, HasTheReportsItsItemsDeclare) {
  const hid::ReportDescriptor d = hid::parse_report_descriptor(sidewinder_ff2_report_descriptor());
  EXPECT_EQ(sidewinder_ff2_report_descriptor().size(), 1343u) << "the recorded wDescriptorLength";
  EXPECT_TRUE(d.uses_report_ids);
  EXPECT_EQ(d.report_ids(ReportType::Input), (std::vector<std::uint8_t>{1, 2}));
  EXPECT_EQ(d.report_ids(ReportType::Output), (std::vector<std::uint8_t>{1, 2, 3, 4, 5, 6, 7, 8, 10, 11, 12, 13, 14}));
  EXPECT_EQ(d.report_ids(ReportType::Feature), (std::vector<std::uint8_t>{1, 2, 3}));
  // Input 1: X 10 + 6 pad, Y 10 + 6, Rz 6 + 2, slider 7 + 1, hat 4 + 4, 8 buttons, 4 x 8 pad = 96
  // bits, 12 bytes + ID. Input 2 (PID State): 5 + 3 pad + 1 + 7 = 16 bits.
  EXPECT_EQ(d.report_bytes(ReportType::Input, 1), 13u);
  EXPECT_EQ(d.report_bytes(ReportType::Input, 2), 3u);
  // Set Effect: index 8, type 8, duration/repeat/sample 3 x 16, gain 8, trigger 8, axes 2,
  // direction enable 1, pad 5, direction 2 x 8, start delay 16 = 120 bits: 15 + ID = the OUT
  // endpoint's recorded 16-byte packet.
  EXPECT_EQ(d.report_bytes(ReportType::Output, 1), 16u);
  EXPECT_EQ(d.report_bytes(ReportType::Output, 2), 8u);   // Set Envelope: 8 + 2 x 8 + 2 x 16
  EXPECT_EQ(d.report_bytes(ReportType::Output, 3), 9u);   // Set Condition: 8 + 4 + 2 x 2 + 8 + 2 x 8 + 2 x 8 + 8
  EXPECT_EQ(d.report_bytes(ReportType::Output, 4), 7u);   // Set Periodic: 8 x 4 + 16
  EXPECT_EQ(d.report_bytes(ReportType::Output, 5), 4u);   // Set Constant Force: 8 + 16
  EXPECT_EQ(d.report_bytes(ReportType::Output, 7), 16u);  // Custom Force Data: 8 + 16 + 12 x 8
  EXPECT_EQ(d.report_bytes(ReportType::Output, 10), 4u);  // Effect Operation: 3 x 8
  EXPECT_EQ(d.report_bytes(ReportType::Output, 12), 2u);  // Device Control
  EXPECT_EQ(d.report_bytes(ReportType::Output, 14), 5u);  // Set Custom Force: 8 + 8 + 16
  EXPECT_EQ(d.report_bytes(ReportType::Feature, 1), 4u);  // Create New Effect: 8 + 10 + 6 pad
  EXPECT_EQ(d.report_bytes(ReportType::Feature, 2), 5u);  // Block Load: 8 + 8 + 16
  EXPECT_EQ(d.report_bytes(ReportType::Feature, 3), 5u);  // PID Pool: 16 + 8 + 2 + 6 pad
}

TEST(Ff2Descriptor, FieldsHaveTheirOffsetsRangesAndCollections) {
  const hid::ReportDescriptor d = hid::parse_report_descriptor(sidewinder_ff2_report_descriptor());
  const hid::ReportField& x = field(d, ReportType::Input, 1, hid::usage(0x01, 0x30));
  EXPECT_EQ(x.bit_offset, 0u);
  EXPECT_EQ(x.bit_size, 10u);
  EXPECT_EQ(x.logical_min, -512);  // 16 00 FE
  EXPECT_EQ(x.logical_max, 511);
  EXPECT_TRUE(x.variable);
  EXPECT_EQ(x.collections, (std::vector<std::uint32_t>{hid::usage(0x01, 0x01), hid::usage(0x01, 0x04)}))
      << "Pointer (physical) inside Joystick (application)";
  EXPECT_EQ(field(d, ReportType::Input, 1, hid::usage(0x01, 0x31)).bit_offset, 16u);
  const hid::ReportField& hat = field(d, ReportType::Input, 1, hid::usage(0x01, 0x39));
  EXPECT_EQ(hat.bit_offset, 48u);
  EXPECT_TRUE(hat.null_state);  // 81 42
  const hid::ReportField& buttons = field(d, ReportType::Input, 1, hid::usage(0x09, 0x01));
  EXPECT_EQ(buttons.bit_offset, 56u);
  EXPECT_EQ(buttons.count, 8u);
  EXPECT_EQ(buttons.element_usage(7), hid::usage(0x09, 0x08)) << "Usage Minimum/Maximum 1..8";

  const hid::ReportField& magnitude = field(d, ReportType::Output, 5, hid::usage(0x0F, 0x70));
  EXPECT_EQ(magnitude.bit_offset, 8u);
  EXPECT_EQ(magnitude.bit_size, 16u);
  EXPECT_EQ(magnitude.logical_min, -255);  // 16 01 FF
  EXPECT_EQ(magnitude.logical_max, 255);   // 26 FF 00 after a negative minimum
  EXPECT_EQ(hid::read_field(Bytes{0x00, 0x01, 0xFF}, magnitude), -255);  // block, then -255 in 16 bits

  const hid::ReportField& type = field(d, ReportType::Output, 1, hid::usage(0x0F, 0x25));
  EXPECT_FALSE(type.variable);
  EXPECT_EQ(type.logical_min, 1);  // 25 0C before 15 01
  EXPECT_EQ(type.logical_max, 12);
  ASSERT_EQ(type.usages.size(), 12u);
  EXPECT_EQ(type.array_usage(1), hid::usage(0x0F, 0x26)) << "ET Constant Force";

  const hid::ReportField& direction = field(d, ReportType::Output, 1, hid::usage(0x0A, 0x01));
  EXPECT_EQ(direction.bit_offset, 88u);
  EXPECT_EQ(direction.count, 2u);
  EXPECT_EQ(direction.collections.at(0), hid::usage(0x0F, 0x57)) << "in Direction";
  EXPECT_EQ(direction.collections.at(1), hid::usage(0x0F, 0x21)) << "in Set Effect";
  EXPECT_DOUBLE_EQ(direction.physical(255), 360.0) << "47 A0 8C 00 00 (36000) at Unit Exponent -2";
  const hid::ReportField& duration = field(d, ReportType::Output, 1, hid::usage(0x0F, 0x50));
  EXPECT_DOUBLE_EQ(duration.physical(1000), 1.0) << "ms: Unit Exponent -3 of seconds";

  const hid::ReportField& control = field(d, ReportType::Output, 12, hid::usage(0x0F, 0x96));
  EXPECT_FALSE(control.variable);
  EXPECT_EQ(control.array_usage(3), hid::usage(0x0F, 0x99)) << "value 3: DC Stop All Effects";
  const hid::ReportField& available = field(d, ReportType::Feature, 2, hid::usage(0x0F, 0xAC));
  EXPECT_EQ(available.logical_max, 65535);  // 27 FF FF 00 00
}

TEST(ReportDescriptorParser, PushPopUsageRangesAndExtendedUsages) {
  const Bytes d{0x05, 0x09,                    // Usage Page (Button)
                0xA1, 0x01,                    // Collection (Application) with no usage
                0x15, 0x81, 0x25, 0x7F,        // Logical -127..127
                0xA4,                          // Push
                0x15, 0x00, 0x25, 0xFF,        // Logical 0..255 (unsigned: minimum 0)
                0x19, 0x03, 0x29, 0x05,        // Usage Minimum 3, Maximum 5
                0x75, 0x08, 0x95, 0x03, 0x81, 0x02,  // Input 3 x 8
                0xB4,                          // Pop: -127..127 again
                0x0B, 0x01, 0x00, 0x0A, 0x00,  // Usage (Ordinal 1), extended
                0x75, 0x08, 0x95, 0x01, 0x81, 0x02, 0xC0};
  const hid::ReportDescriptor r = hid::parse_report_descriptor(d);
  ASSERT_EQ(r.fields.size(), 2u);
  EXPECT_EQ(r.fields[0].logical_max, 255);
  EXPECT_EQ(r.fields[0].usages, (std::vector<std::uint32_t>{0x90003, 0x90004, 0x90005}));
  EXPECT_EQ(r.fields[1].logical_min, -127);
  EXPECT_EQ(r.fields[1].logical_max, 127);
  EXPECT_EQ(r.fields[1].bit_offset, 24u);
  EXPECT_EQ(r.fields[1].usages, (std::vector<std::uint32_t>{0x0A0001}));
  EXPECT_FALSE(r.uses_report_ids);
  EXPECT_EQ(r.report_bytes(ReportType::Input, 0), 4u);
}

TEST(ReportDescriptorParser, BadInputNamesTheByte) {
  const auto fails_at = [](const Bytes& d, const std::string& at) {
    try {
      hid::parse_report_descriptor(d);
      ADD_FAILURE() << "parsed";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("byte " + at), std::string::npos) << e.what();
    }
  };
  fails_at({0x05, 0x01, 0x26, 0xFF}, "2");  // truncated Logical Maximum
  fails_at({0x05, 0x01, 0xC0}, "2");        // End Collection alone
  fails_at({0xB4}, "0");                    // Pop without Push
  fails_at({0x05, 0x01, 0x85, 0x00}, "2");  // Report ID 0
  fails_at({0x05, 0x01, 0xA1, 0x01}, "2");  // a collection never ended
  fails_at({0x19, 0x05, 0x29, 0x01, 0x81, 0x02}, "2");  // Usage Maximum below Minimum
}

// ---- the model ----

// Report IDs and values of the FF2's descriptor (by hand from the .hex).
constexpr std::uint8_t kSetEffect = 1, kSetConstantForce = 5, kEffectOperation = 10, kBlockFree = 11,
                       kDeviceControl = 12, kDeviceGain = 13, kCreateNewEffect = 1, kBlockLoad = 2, kPool = 3;
constexpr std::uint8_t kStart = 1, kStartSolo = 2, kStop = 3;                   // Effect Operation array
constexpr std::uint8_t kEnable = 1, kDisable = 2, kStopAll = 3, kReset = 4, kPause = 5, kContinue = 6;
constexpr std::uint8_t kSuccess = 1, kFull = 2, kError = 3;                      // Block Load Status array
constexpr std::int16_t kHalf = 16448;  // round(32767 x 128 / 255): magnitude 128 of 255 ("half"; 127.5 is no value)

ControlReply get_feature(HidPidDevice& d, std::uint8_t id) {
  return d.control(SetupPacket{0xA1, 0x01, static_cast<std::uint16_t>(0x0300 | id), 0, 64}, {});
}
ControlReply set_feature(HidPidDevice& d, const Bytes& r) {
  return d.control(SetupPacket{0x21, 0x09, static_cast<std::uint16_t>(0x0300 | r[0]), 0, static_cast<std::uint16_t>(r.size())}, r);
}

// Create New Effect (type 1, ET Constant Force; Byte Count 0), then Block Load: {block, status}.
std::pair<int, int> create(HidPidDevice& d, std::uint8_t type = 1) {
  EXPECT_FALSE(set_feature(d, {kCreateNewEffect, type, 0, 0}).stall);
  const ControlReply r = get_feature(d, kBlockLoad);
  EXPECT_FALSE(r.stall);
  EXPECT_EQ(r.data.size(), 5u);
  if (r.data.size() < 3) return {0, 0};
  EXPECT_EQ(r.data[0], kBlockLoad);
  return {r.data[1], r.data[2]};
}

// Set Effect: constant force, infinite duration (0xFFFF, outside 0..32767), gain 255, no trigger,
// X and Y enabled, Direction Enable, direction ordinal 1 = `direction` (0..255 over 0..360 deg).
Bytes set_effect(std::uint8_t block, std::uint8_t direction, std::uint16_t duration_ms = 0xFFFF, bool direction_enable = true,
                 std::uint8_t axes = 0x3, std::uint8_t gain = 255) {
  Bytes r(16, 0);
  r[0] = kSetEffect;
  r[1] = block;
  r[2] = 1;  // ET Constant Force
  r[3] = static_cast<std::uint8_t>(duration_ms & 0xFF);
  r[4] = static_cast<std::uint8_t>(duration_ms >> 8);
  r[9] = gain;
  r[11] = static_cast<std::uint8_t>(axes | (direction_enable ? 0x4 : 0));  // X bit 0, Y bit 1, Direction Enable bit 2
  r[12] = direction;
  return r;
}
Bytes constant_force(std::uint8_t block, std::int16_t magnitude) {
  const auto m = static_cast<std::uint16_t>(magnitude);
  return {kSetConstantForce, block, static_cast<std::uint8_t>(m & 0xFF), static_cast<std::uint8_t>(m >> 8)};
}
Bytes operation(std::uint8_t block, std::uint8_t op) { return {kEffectOperation, block, op, 1}; }

// A device with actuators enabled, full device gain and one constant force at `direction`,
// magnitude 128, started.
std::unique_ptr<HidPidDevice> playing(std::uint8_t direction, std::int16_t magnitude = 128) {
  auto d = sidewinder_ff2();
  d->configured();
  d->interrupt_out(Bytes{kDeviceControl, kReset});
  d->interrupt_out(Bytes{kDeviceControl, kEnable});
  d->interrupt_out(Bytes{kDeviceGain, 255});
  const auto [block, status] = create(*d);
  EXPECT_EQ(status, kSuccess);
  d->interrupt_out(set_effect(static_cast<std::uint8_t>(block), direction));
  d->interrupt_out(constant_force(static_cast<std::uint8_t>(block), magnitude));
  d->interrupt_out(operation(static_cast<std::uint8_t>(block), kStart));
  return d;
}

TEST(HidPidDevice, ServesItsDescriptorsAsRecorded) {
  auto d = sidewinder_ff2();
  EXPECT_EQ(d->identity().vendor_id, 0x045E);
  EXPECT_EQ(d->identity().product_id, 0x001B);
  EXPECT_EQ(d->identity().bcd_device, 0x0A00);
  const ControlReply r = d->control(SetupPacket{0x81, 0x06, 0x2200, 0, 4096}, {});
  ASSERT_FALSE(r.stall);
  EXPECT_EQ(r.data.size(), 1343u);
  const ControlReply h = d->control(SetupPacket{0x81, 0x06, 0x2100, 0, 9}, {});
  ASSERT_EQ(h.data.size(), 9u);
  EXPECT_EQ(h.data[7] | h.data[8] << 8, 1343) << "wDescriptorLength";
  const Bytes f = d->function_descriptors();
  ASSERT_EQ(f.size(), 9u + 9u + 7u + 7u);
  EXPECT_EQ(Bytes(f.begin() + 18, f.end()), (Bytes{7, 5, 0x81, 3, 64, 0, 1, 7, 5, 0x02, 3, 16, 0, 4}));
  EXPECT_TRUE(d->control(SetupPacket{0x21, 0x0B, 0, 0, 0}, {}).stall) << "SET_PROTOCOL: not a boot device";
  EXPECT_FALSE(d->control(SetupPacket{0x21, 0x0A, 0, 0, 0}, {}).stall) << "SET_IDLE";
}

TEST(HidPidDevice, BlockLoadGivesBlocksInTurnAndFullWhenThePoolIsExhausted) {
  auto d = sidewinder_ff2();
  const ControlReply pool = get_feature(*d, kPool);
  ASSERT_EQ(pool.data.size(), 5u);
  EXPECT_EQ(pool.data[0], kPool);
  EXPECT_EQ(pool.data[4] & 0x1, 1) << "Device Managed Pool";
  EXPECT_GE(pool.data[3], 2) << "Simultaneous Effects Max";
  EXPECT_EQ(create(*d), std::make_pair(1, int{kSuccess}));
  EXPECT_EQ(create(*d), std::make_pair(2, int{kSuccess}));
  int blocks = 2;
  std::pair<int, int> last;
  while ((last = create(*d)).second == kSuccess) EXPECT_EQ(last.first, ++blocks);
  // Effect Block Index runs 1..40 in Block Load: the 41st has no index to name it.
  EXPECT_EQ(blocks, 40);
  EXPECT_EQ(last.second, kFull);
  EXPECT_EQ(last.first, 0);
  const ControlReply load = get_feature(*d, kBlockLoad);
  EXPECT_EQ(load.data[3] | load.data[4] << 8, 0) << "RAM Pool Available";
  EXPECT_EQ(d->state().effects_in_use, 40);
  // Block Free gives block 7 back; the next effect gets it.
  d->interrupt_out(Bytes{kBlockFree, 7});
  EXPECT_EQ(create(*d), std::make_pair(7, int{kSuccess}));
  // An effect type outside 1..12 is an error, not a block.
  d->interrupt_out(Bytes{kBlockFree, 7});
  EXPECT_EQ(create(*d, 13).second, kError);
  // Device Reset frees every block.
  d->interrupt_out(Bytes{kDeviceControl, kReset});
  EXPECT_EQ(d->state().effects_in_use, 0);
  EXPECT_EQ(create(*d), std::make_pair(1, int{kSuccess}));
}

TEST(HidPidDevice, ConstantForceAtZeroDegreesPushesTowardPlusY) {
  // Polar direction 0 is north (-Y, away from the user) and names where the force comes from: it
  // pushes the handle toward +Y.
  auto d = playing(0);
  EXPECT_EQ(d->state().torque[0], 0);
  EXPECT_EQ(d->state().torque[1], kHalf);
}

TEST(HidPidDevice, ConstantForceAtNinetyDegreesPushesTowardMinusX) {
  // 90 degrees is east (+X): the force comes from the right and pushes the handle left. Ordinal 64
  // is 64 x 360 / 255 = 90.35 degrees: cos gives Y 0.006 of the force, ~100 units.
  auto d = playing(64);
  EXPECT_NEAR(d->state().torque[0], -kHalf, 2);
  EXPECT_NEAR(d->state().torque[1], 0, 120);
  // A negative magnitude reverses it.
  d->interrupt_out(constant_force(1, -128));
  EXPECT_NEAR(d->state().torque[0], kHalf, 2);
}

TEST(HidPidDevice, StopBlockFreeStopAllDisableAndPauseEndTheForce) {
  auto d = playing(0);
  ASSERT_EQ(d->state().torque[1], kHalf);
  d->interrupt_out(operation(1, kStop));
  EXPECT_EQ(d->state().torque[1], 0);
  d->interrupt_out(operation(1, kStart));
  EXPECT_EQ(d->state().torque[1], kHalf);
  d->interrupt_out(Bytes{kDeviceControl, kStopAll});
  EXPECT_EQ(d->state().torque[1], 0);
  d->interrupt_out(operation(1, kStartSolo));
  EXPECT_EQ(d->state().torque[1], kHalf);
  d->interrupt_out(Bytes{kDeviceControl, kDisable});
  EXPECT_EQ(d->state().torque[1], 0);
  EXPECT_FALSE(d->state().actuators_enabled);
  d->interrupt_out(Bytes{kDeviceControl, kEnable});
  EXPECT_EQ(d->state().torque[1], kHalf) << "the effect kept playing";
  d->interrupt_out(Bytes{kDeviceControl, kPause});
  EXPECT_EQ(d->state().torque[1], 0);
  d->interrupt_out(Bytes{kDeviceControl, kContinue});
  EXPECT_EQ(d->state().torque[1], kHalf);
  d->interrupt_out(Bytes{kBlockFree, 1});
  EXPECT_EQ(d->state().torque[1], 0);
  EXPECT_EQ(d->state().effects_in_use, 0);
}

TEST(HidPidDevice, GainsScaleTheForce) {
  auto d = playing(0, 255);
  EXPECT_EQ(d->state().torque[1], 32767);
  d->interrupt_out(Bytes{kDeviceGain, 128});
  EXPECT_EQ(d->state().torque[1], 16448);  // 128/255
  d->interrupt_out(set_effect(1, 0, 0xFFFF, true, 0x3, 128));
  EXPECT_EQ(d->state().torque[1], std::lround(32767.0 * 128 / 255 * 128 / 255));
}

TEST(HidPidDevice, AnEffectWithADurationStopsByItself) {
  auto d = playing(0);
  d->interrupt_out(set_effect(1, 0, 30));  // 30 ms (Unit Exponent -3 s)
  d->interrupt_out(operation(1, kStart));
  EXPECT_EQ(d->state().torque[1], kHalf);
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
  d->update();
  EXPECT_EQ(d->state().torque[1], 0);
  EXPECT_EQ(d->state().effects_playing, 0);
}

TEST(HidPidDevice, WithoutDirectionEnableOnlyTheEnabledAxesGetTheDirectionsComponents) {
  auto d = playing(0);
  d->interrupt_out(set_effect(1, 0, 0xFFFF, false, 0x2));  // Y alone, 0 degrees: all of it
  EXPECT_EQ(d->state().torque[1], kHalf);
  d->interrupt_out(set_effect(1, 0, 0xFFFF, false, 0x1));  // X alone, 0 degrees: none
  EXPECT_EQ(d->state().torque[0], 0);
  EXPECT_EQ(d->state().torque[1], 0);
  d->interrupt_out(set_effect(1, 191, 0xFFFF, false, 0x1));  // X alone, 270 degrees (191 = 269.6): +X
  EXPECT_NEAR(d->state().torque[0], kHalf, 2);
}

TEST(HidPidDevice, DeviceControlOverTheControlPipeToo) {
  auto d = playing(0);
  const Bytes disable{kDeviceControl, kDisable};
  EXPECT_FALSE(d->control(SetupPacket{0x21, 0x09, 0x0200 | kDeviceControl, 0, 2}, disable).stall);
  EXPECT_EQ(d->state().torque[1], 0);
}

TEST(HidPidDevice, ReportsEachTorqueChangeToItsObserver) {
  auto d = sidewinder_ff2();
  std::mutex m;
  std::vector<TorqueUpdate> seen;
  d->on_torque([&](const TorqueUpdate& u) {
    std::lock_guard lock(m);
    seen.push_back(u);
  });
  d->configured();
  d->interrupt_out(Bytes{kDeviceControl, kEnable});
  create(*d);
  d->interrupt_out(set_effect(1, 0));
  d->interrupt_out(constant_force(1, 128));
  d->interrupt_out(operation(1, kStart));
  d->interrupt_out(operation(1, kStop));
  std::lock_guard lock(m);
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].axis, 1);
  EXPECT_EQ(seen[0].torque, kHalf);
  EXPECT_EQ(seen[1].torque, 0);
  EXPECT_EQ(d->state().torque_updates[1], 2u);
}

TEST(HidPidDevice, TheInputReportCarriesThePositionOnChange) {
  auto d = sidewinder_ff2();
  d->configured();
  Bytes r;
  ASSERT_TRUE(d->next_interrupt_in(r, std::chrono::milliseconds(10))) << "the first report after configuration";
  d->interrupt_in_done(true);
  ASSERT_EQ(r.size(), 13u);
  EXPECT_EQ(r[0], 1);
  EXPECT_EQ(r[7] & 0x0F, 0x0F) << "hat null: outside 0..7";
  EXPECT_EQ(r[8], 0) << "buttons released";
  EXPECT_FALSE(d->next_interrupt_in(r, std::chrono::milliseconds(5))) << "nothing changed";
  d->set_position(0, 1.0);   // X at its logical maximum, 511 = 0x1FF
  d->set_position(1, -1.0);  // Y at its minimum, -512 = 0x200 in 10 bits
  ASSERT_TRUE(d->next_interrupt_in(r, std::chrono::milliseconds(10)));
  EXPECT_EQ(r[1] | (r[2] & 0x03) << 8, 0x1FF);
  EXPECT_EQ(r[3] | (r[4] & 0x03) << 8, 0x200);
  EXPECT_FALSE(d->next_interrupt_in(r, std::chrono::milliseconds(5))) << "one report holds the newest state";
  // SET_IDLE 4 ms: the report comes again without a change (HID 1.11 section 7.2.4).
  d->control(SetupPacket{0x21, 0x0A, 0x0100, 0, 0}, {});
  EXPECT_TRUE(d->next_interrupt_in(r, std::chrono::milliseconds(20)));
}

// ---- Sandpaper's own driver on the model ----

namespace usb = runtime::usb;
using usb::UsbStatus;

// The model as a UsbTransport, as driver_on_wheel_firmware_test.cpp's FirmwareTransport does the
// firmware: control requests on its control pipe (HID 1.11 section 7.2), output reports on its
// interrupt OUT endpoint, input reports from its interrupt IN queue.
class ModelTransport final : public usb::UsbTransport {
 public:
  explicit ModelTransport(HidPidDevice& d) : d_(d) {}
  UsbStatus report_descriptor(std::vector<std::uint8_t>& descriptor) override {
    const ControlReply r = d_.control(SetupPacket{0x81, 0x06, 0x2200, 0, 4096}, {});
    if (r.stall) return UsbStatus::Stalled;
    descriptor = r.data;
    return UsbStatus::Ok;
  }
  UsbStatus detach_kernel_driver() override { return UsbStatus::Ok; }
  UsbStatus attach_kernel_driver() override { return UsbStatus::Ok; }
  UsbStatus claim_interface() override { return UsbStatus::Ok; }
  UsbStatus release_interface() override { return UsbStatus::Ok; }
  UsbStatus read_input(std::span<std::uint8_t> buffer, std::size_t& length, unsigned timeout_ms) noexcept override {
    std::vector<std::uint8_t> report;
    if (!d_.next_interrupt_in(report, std::chrono::milliseconds(timeout_ms))) return UsbStatus::Timeout;
    d_.interrupt_in_done(true);
    length = std::min(report.size(), buffer.size());
    std::copy_n(report.begin(), length, buffer.begin());
    return UsbStatus::Ok;
  }
  UsbStatus write_output(std::span<const std::uint8_t> report) noexcept override {
    d_.interrupt_out(report);
    return UsbStatus::Ok;
  }
  UsbStatus set_feature(std::span<const std::uint8_t> report) override {
    const SetupPacket s{0x21, 0x09, static_cast<std::uint16_t>(0x0300 | report[0]), 0,
                        static_cast<std::uint16_t>(report.size())};
    return d_.control(s, report).stall ? UsbStatus::Stalled : UsbStatus::Ok;
  }
  UsbStatus get_feature(std::uint8_t id, std::span<std::uint8_t> buffer, std::size_t& length) override {
    const SetupPacket s{0xA1, 0x01, static_cast<std::uint16_t>(0x0300 | id), 0, static_cast<std::uint16_t>(buffer.size())};
    const ControlReply r = d_.control(s, {});
    if (r.stall) return UsbStatus::Stalled;
    length = std::min(r.data.size(), buffer.size());
    std::copy_n(r.data.begin(), length, buffer.begin());
    return UsbStatus::Ok;
  }

 private:
  HidPidDevice& d_;
};

// A two-axis device file for the FF2 model. Magnitude runs -255..255 (Set Constant Force), so
// command_max 255; 10 N full scale is assumed, as for the OpenFFBoard. command_sense -1 on both:
// the driver's X effect points at 90 degrees and its Y effect at 180 (Direction Enable, polar), which
// the model, taking the direction as where the force comes from, plays toward -X and -Y.
const char* kFf2DeviceFile = R"(
schema = "sandpaper-device/1"
name = "sidewinder-ff2-lab"
description = "The USB lab's SideWinder Force Feedback 2 model (HID PID 1.0), for tests"
command_unit = "PID magnitude"
[force]
max_continuous = "10 N"
command_max = 255
[force.x]
newtons_per_command_unit = 0.0392156862745098
command_sense = -1
[force.y]
newtons_per_command_unit = 0.0392156862745098
command_sense = -1
[position]
resolution = "0.1 mm"
[workspace]
shape = "rectangle"
width = "100 mm"
height = "100 mm"
[usb]
vendor_id = 0x045E
product_id = 0x001B
out_interval = "4 ms"
[servo_rate_hz]
min = 200
max = 1000
[calibration]
status = "uncalibrated"
method = "none: a lab model"
source = "USB HID PID 1.0; the FF2's recorded descriptors"
)";

usb::HidPidOptions synchronous() {
  usb::HidPidOptions o;
  o.io = usb::HidPidIo::CallingThread;
  o.read_timeout_ms = 20;
  o.open_read_timeout_ms = 50;
  return o;
}

TEST(DriverOnHidPidModel, OpensTheFf2WithOneEffectPerAxis) {
  const calibration::DeviceCalibration file = calibration::parse_device_text(kFf2DeviceFile, "sidewinder-ff2-lab");
  auto d = sidewinder_ff2();
  d->configured();
  ModelTransport t(*d);
  {
    usb::HidPidJoystick js(t, file, synchronous());
    EXPECT_EQ(js.effect_block_index(0), 1);
    EXPECT_EQ(js.effect_block_index(1), 2);
    const HidPidDeviceState s = d->state();
    EXPECT_TRUE(s.actuators_enabled);
    EXPECT_EQ(s.effects_in_use, 2);
    EXPECT_EQ(s.effects_playing, 2);
    EXPECT_EQ(s.reports_rejected, 0u);
    // +3 N on Y: magnitude -77 (3 N = 76.5 -> 77 units of 255, command_sense -1) at 180 degrees
    // (ordinal 128 of 255: 180.7) pushes toward +Y with 77/255 of full scale, x cos(0.7 degrees).
    ASSERT_TRUE(js.write_force_rt({0.0, 3.0}));
    EXPECT_NEAR(d->state().torque[1], 32767.0 * 77 / 255, 0.005 * 32767.0 * 77 / 255);
    EXPECT_NEAR(d->state().torque[0], 0, 0.02 * 32767.0 * 77 / 255) << "next to nothing on X";
    ASSERT_TRUE(js.write_force_rt({0.0, -3.0}));
    EXPECT_LT(d->state().torque[1], 0);
  }
  const HidPidDeviceState s = d->state();
  EXPECT_EQ(s.effects_in_use, 0) << "close freed the effects";
  EXPECT_FALSE(s.actuators_enabled);
  EXPECT_EQ(s.torque[0], 0);
  EXPECT_EQ(s.torque[1], 0);
}

// The driver's X effect has Direction Enable and one polar direction, 90 degrees (hid_pid_open.cpp,
// Set Effect), so a device that reads the direction as the PID polar angle plays it on X. (With
// Direction Enable clear and the ordinal at 360 degrees, as the driver once sent it, this model
// gave X nothing: it takes the ordinal as an angle where the OpenFFBoard reads it linearly.)
TEST(DriverOnHidPidModel, TheDriversXEffectPlaysOnX) {
  const calibration::DeviceCalibration file = calibration::parse_device_text(kFf2DeviceFile, "sidewinder-ff2-lab");
  auto d = sidewinder_ff2();
  d->configured();
  ModelTransport t(*d);
  usb::HidPidJoystick js(t, file, synchronous());
  ASSERT_TRUE(js.write_force_rt({3.0, 0.0}));
  EXPECT_EQ(js.last_command()[0], -77) << "3 N, command_sense -1";
  // Ordinal 64 of 255 is 90.35 degrees: all but sin's 2e-5 on X, 0.6 % on Y.
  EXPECT_NEAR(d->state().torque[0], 32767.0 * 77 / 255, 0.005 * 32767.0 * 77 / 255) << "+3 N pushes toward +X";
  EXPECT_NEAR(d->state().torque[1], 0, 0.02 * 32767.0 * 77 / 255);
  ASSERT_TRUE(js.write_force_rt({-10.0, 0.0}));
  EXPECT_LT(d->state().torque[0], 0);
}

TEST(DriverOnHidPidModel, ThePositionIsTheInputReportsXAndY) {
  const calibration::DeviceCalibration file = calibration::parse_device_text(kFf2DeviceFile, "sidewinder-ff2-lab");
  auto d = sidewinder_ff2();
  d->configured();
  d->set_position(0, 0.5);
  d->set_position(1, -0.5);
  ModelTransport t(*d);
  usb::HidPidJoystick js(t, file, synchronous());
  d->set_position(0, 0.5001);  // a change, so a report comes now (reports go on change)
  glm::dvec2 p{0, 0};
  double t_s = 0;
  for (int i = 0; i < 10 && p.x == 0; ++i) ASSERT_TRUE(js.read_position_rt(t_s += 0.001, p));
  // Half of the positive range: a quarter of the 100 mm width from centre, to a 10-bit step.
  EXPECT_NEAR(p.x, 0.025, 2 * 0.1e-3);
  EXPECT_NEAR(p.y, -0.025, 2 * 0.1e-3);
}

}  // namespace
}  // namespace sandpaper::usb_lab
