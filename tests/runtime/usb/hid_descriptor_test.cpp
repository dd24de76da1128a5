// The report descriptor parser on the hand-written OpenFFBoard-like joystick descriptor: every field
// the driver uses is found with the report ID, bit offset, size and logical range the descriptor gives.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sandpaper/runtime/usb/hid_descriptor.hpp"
#include "usb_test_support.hpp"

namespace sandpaper::runtime::usb {
namespace {

struct Expect {
  ReportType type;
  std::uint32_t report, field;
  int id, offset, size, min, max;
};

TEST(HidDescriptor, FindsEveryFieldOfTheJoystickAndItsPidReports) {
  const auto d = parse_hid_report_descriptor(testing::test_descriptor());
  EXPECT_TRUE(d.uses_report_ids);
  EXPECT_TRUE(d.has_pid_page());
  using enum ReportType;
  const Expect expected[] = {
      {Input, 0, kUsageX, 1, 8, 16, -32767, 32767},
      {Input, 0, kUsageY, 1, 24, 16, -32767, 32767},
      {Output, pid::kSetEffectReport, pid::kEffectBlockIndex, 1, 0, 8, 1, 40},
      {Output, pid::kSetEffectReport, pid::kEffectType, 1, 8, 8, 1, 12},
      {Output, pid::kSetEffectReport, pid::kDuration, 1, 16, 16, 0, 32767},
      {Output, pid::kSetEffectReport, pid::kTriggerRepeatInterval, 1, 32, 16, 0, 32767},
      {Output, pid::kSetEffectReport, pid::kSamplePeriod, 1, 48, 16, 0, 32767},
      {Output, pid::kSetEffectReport, pid::kStartDelay, 1, 64, 16, 0, 32767},
      {Output, pid::kSetEffectReport, pid::kGain, 1, 80, 8, 0, 255},
      {Output, pid::kSetEffectReport, pid::kTriggerButton, 1, 88, 8, 1, 8},
      {Output, pid::kSetEffectReport, kUsageX, 1, 96, 1, 0, 1},
      {Output, pid::kSetEffectReport, kUsageY, 1, 97, 1, 0, 1},
      {Output, pid::kSetEffectReport, pid::kDirectionEnable, 1, 98, 1, 0, 1},
      {Output, pid::kSetEffectReport, usage(kOrdinalPage, 1), 1, 104, 16, 0, 36000},
      {Output, pid::kSetEffectReport, usage(kOrdinalPage, 2), 1, 120, 16, 0, 36000},
      {Output, pid::kSetConstantForceReport, pid::kEffectBlockIndex, 5, 0, 8, 1, 40},
      {Output, pid::kSetConstantForceReport, pid::kMagnitude, 5, 8, 16, -10000, 10000},
      {Output, pid::kEffectOperationReport, pid::kEffectBlockIndex, 10, 0, 8, 1, 40},
      {Output, pid::kEffectOperationReport, pid::kEffectOperation, 10, 8, 8, 1, 3},
      {Output, pid::kEffectOperationReport, pid::kLoopCount, 10, 16, 8, 0, 255},
      {Output, pid::kBlockFreeReport, pid::kEffectBlockIndex, 11, 0, 8, 1, 40},
      {Output, pid::kDeviceControlReport, pid::kDeviceControlReport, 12, 0, 8, 1, 6},
      {Feature, pid::kCreateNewEffectReport, pid::kEffectType, 17, 0, 8, 1, 12},
      {Feature, pid::kCreateNewEffectReport, pid::kByteCount, 17, 8, 10, 0, 511},
      {Feature, pid::kBlockLoadReport, pid::kEffectBlockIndex, 18, 0, 8, 1, 40},
      {Feature, pid::kBlockLoadReport, pid::kBlockLoadStatus, 18, 8, 8, 1, 3},
      {Feature, pid::kPoolReport, pid::kRamPoolSize, 19, 0, 16, 0, 65535},
      {Feature, pid::kPoolReport, pid::kSimultaneousEffectsMax, 19, 16, 8, 0, 255},
  };
  for (const auto& e : expected) {
    SCOPED_TRACE(::testing::Message() << "report usage 0x" << std::hex << e.report << " field 0x" << e.field);
    const HidField* f = d.find(e.type, e.report, e.field);
    ASSERT_NE(f, nullptr);
    EXPECT_EQ(f->report_id, e.id);
    EXPECT_EQ(f->bit_offset, static_cast<std::uint32_t>(e.offset));
    EXPECT_EQ(f->bit_size, static_cast<std::uint32_t>(e.size));
    EXPECT_EQ(f->logical_min, e.min);
    EXPECT_EQ(f->logical_max, e.max);
  }
  // The PID State input report (ID 2) does not disturb the position report's layout.
  EXPECT_EQ(d.report_bytes(Input, 1), 6u);
  EXPECT_EQ(d.report_bytes(Input, 2), 3u);
  EXPECT_EQ(d.report_bytes(Output, 1), 18u);
  EXPECT_EQ(d.report_bytes(Output, 5), 4u);
  EXPECT_EQ(d.report_bytes(Feature, 17), 4u);
}

TEST(HidDescriptor, ArrayItemsMapValuesToTheirUsages) {
  const auto d = parse_hid_report_descriptor(testing::test_descriptor());
  const HidField* control = d.find(ReportType::Output, pid::kDeviceControlReport, pid::kDeviceControlReport);
  ASSERT_NE(control, nullptr);
  EXPECT_FALSE(control->variable);
  EXPECT_EQ(control->array_value(pid::kDcEnableActuators), 1);
  EXPECT_EQ(control->array_value(pid::kDcDisableActuators), 2);
  EXPECT_EQ(control->array_value(pid::kDcStopAllEffects), 3);
  EXPECT_EQ(control->array_value(pid::kDcDeviceReset), 4);
  EXPECT_FALSE(control->array_value(pid::kEtConstantForce).has_value());
  const HidField* status = d.find(ReportType::Feature, pid::kBlockLoadReport, pid::kBlockLoadStatus);
  ASSERT_NE(status, nullptr);
  EXPECT_EQ(status->array_usage(1), pid::kBlockLoadSuccess);
  EXPECT_EQ(status->array_usage(2), pid::kBlockLoadFull);
  EXPECT_EQ(status->array_usage(9), 0u);
}

TEST(HidDescriptor, SkipsLongItemsAndReadsUnsignedMaxima) {
  // Usage Page (Generic Desktop), Usage (X), a long item (tag 0x12, two data bytes),
  // Logical Min 0, Logical Max 0xFF in one byte (= 255), 8 bits x 1, Input.
  const std::vector<std::uint8_t> bytes = {0x05, 0x01, 0x09, 0x30, 0xFE, 0x02, 0x12, 0xAA, 0xBB,
                                           0x15, 0x00, 0x25, 0xFF, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02};
  const auto d = parse_hid_report_descriptor(bytes);
  EXPECT_FALSE(d.uses_report_ids);
  const HidField* x = d.find(ReportType::Input, 0, kUsageX);
  ASSERT_NE(x, nullptr);
  EXPECT_EQ(x->logical_max, 255);
  EXPECT_EQ(x->bit_offset, 0u);
  EXPECT_FALSE(d.has_pid_page());
}

TEST(HidDescriptor, RefusesTruncatedAndUnbalancedDescriptors) {
  EXPECT_THROW(parse_hid_report_descriptor(std::vector<std::uint8_t>{0x05}), HidDescriptorError);
  EXPECT_THROW(parse_hid_report_descriptor(std::vector<std::uint8_t>{0xC0}), HidDescriptorError);
  EXPECT_THROW(parse_hid_report_descriptor(std::vector<std::uint8_t>{0xA1, 0x01}), HidDescriptorError);
  auto cut = testing::test_descriptor();
  cut.resize(cut.size() - 1);  // the last End Collection
  EXPECT_THROW(parse_hid_report_descriptor(cut), HidDescriptorError);
}

// The error a descriptor gets, or "" if it parses.
std::string refusal(const std::vector<std::uint8_t>& bytes) {
  try {
    parse_hid_report_descriptor(bytes);
    return "";
  } catch (const HidDescriptorError& e) {
    return e.what();
  }
}

::testing::AssertionResult says(const std::string& error, const std::string& part) {
  if (error.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "the error is \"" << error << "\", without \"" << part << "\"";
}

std::vector<std::uint8_t> operator+(std::vector<std::uint8_t> a, const std::vector<std::uint8_t>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// A descriptor comes from the device: a few bytes of it claimed billions of fields, and the parser
// made them (docs/RELIABILITY.md, F22). Each claim is now checked against Linux hid-core's limits
// before anything is made for it; a claim at the limit still parses.
TEST(HidDescriptor, ClaimsOverLinuxHidLimitsAreRefusedBeforeAnythingIsMadeForThem) {
  using V = std::vector<std::uint8_t>;
  const V one_bit = {0x75, 0x01}, input = {0x81, 0x02}, array_input = {0x81, 0x00};
  // Report Count 0xFFFFFFFF of 1-bit inputs: 4 billion fields from 9 bytes.
  EXPECT_TRUE(says(refusal(one_bit + V{0x97, 0xFF, 0xFF, 0xFF, 0xFF} + input), "byte 2: Report Count 4294967295 is over 12288"));
  EXPECT_TRUE(says(refusal(one_bit + V{0x96, 0x01, 0x30} + input), "Report Count 12289 is over 12288"));
  const auto at_limit = parse_hid_report_descriptor(one_bit + V{0x96, 0x00, 0x30} + input);
  EXPECT_EQ(at_limit.fields.size(), 12288u);
  // A usage range of 65,536 usages (Usage Minimum 0, Usage Maximum 0xFFFF), then an array of
  // 65,535 slots, each of which kept every usage: 17 GB.
  const V range = {0x05, 0x09, 0x19, 0x00, 0x2A, 0xFF, 0xFF};
  EXPECT_TRUE(says(refusal(range + one_bit + V{0x96, 0xFF, 0xFF} + array_input), "byte 4: more than 12288 usages before one main item"));
  // Usages 1..12288 are allowed; 100 array slots keeping them all are over the total.
  const V full_range = {0x05, 0x09, 0x19, 0x01, 0x2A, 0x00, 0x30, 0x75, 0x10};
  EXPECT_TRUE(says(refusal(full_range + V{0x95, 0x64} + array_input), "arrays with more than 1048576 usages in all"));
  EXPECT_EQ(parse_hid_report_descriptor(full_range + V{0x95, 0x50} + array_input).fields.size(), 80u);
  // A report longer than 16,384 bytes: 600 fields of 256 bits.
  const V wide = {0x76, 0x00, 0x01};
  EXPECT_TRUE(says(refusal(wide + V{0x96, 0x58, 0x02} + input), "input report 0 grows to 19200 bytes, over the 16384"));
  EXPECT_EQ(parse_hid_report_descriptor(wide + V{0x96, 0xFF, 0x01} + input).report_bytes(ReportType::Input, 0), 16352u);
  // Six reports of 12,288 one-bit fields: each within its size, 73,728 fields in all.
  V many;
  for (std::uint8_t id = 1; id <= 6; ++id) many = many + V{0x85, id} + one_bit + V{0x96, 0x00, 0x30, 0x81, 0x03};
  EXPECT_TRUE(says(refusal(many), "more than 65536 fields in all"));
  // A report ID is one byte: 0x0101 is not report 1.
  EXPECT_TRUE(says(refusal(V{0x86, 0x01, 0x01} + one_bit + V{0x95, 0x01} + input), "report ID 257 is over 255"));
  // A descriptor's length is 16 bits.
  V huge;
  for (int k = 0; k < 32768; ++k) huge.insert(huge.end(), {0x05, 0x01});
  EXPECT_TRUE(says(refusal(huge), "65536 bytes, over the 65535"));
  EXPECT_EQ(refusal(V(huge.begin(), huge.end() - 2)), "");
}

TEST(HidDescriptor, FieldValuesRoundTripWithSign) {
  const auto d = parse_hid_report_descriptor(testing::test_descriptor());
  const HidField& magnitude = *d.find(ReportType::Output, pid::kSetConstantForceReport, pid::kMagnitude);
  std::vector<std::uint8_t> report(4, 0);
  write_field(report, true, magnitude, -2250);
  EXPECT_EQ(report[2], 0x36);
  EXPECT_EQ(report[3], 0xF7);
  EXPECT_EQ(read_field(report, true, magnitude), -2250);
}

}  // namespace
}  // namespace sandpaper::runtime::usb
