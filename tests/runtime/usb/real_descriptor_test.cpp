// The report descriptor parser on REAL force-feedback descriptors (sources, commits and licences in the
// header of each data file):
//   data/openffboard_2axis.hex        OpenFFBoard firmware, hid_2ffb_desc (2-axis FFB, VID:PID 1209:FFB0)
//   data/openffboard_1axis_wheel.hex  OpenFFBoard firmware, hid_1ffb_desc (1-axis FFB wheel)
//   data/ms_sidewinder_ffb2.hex       Microsoft SideWinder Force Feedback 2 (045E:001B), recorded from a device
//
// For the OpenFFBoard the expected report IDs, bit offsets and sizes are NOT taken from the parser: they are
// the firmware's own packed structs and report-ID defines, Ultrawipf/OpenFFBoard
// Firmware/FFBoard/Inc/ffb_defs.h at commit d19d616137f60553b77a9ee78bfddd6fbabba910 (cited as
// ffb_defs.h:LINE), and the way Firmware/FFBoard/Src/HidFFB.cpp (commit 3a4cc0e170a61bbe5298601f10c9e1fdecd6d3d2,
// cited as HidFFB.cpp:LINE) reads them. HidField bit offsets count from the first bit after the report ID
// byte, so a struct member at byte b (report ID at byte 0) is at bit 8 * (b - 1). Feature structs that the
// firmware declares without the ID byte (tinyusb adds/strips it) start at bit 0. Logical ranges come from the
// descriptor source (usb_hid_2ffb_desc.c, same commit as ffb_defs.h).
//
// These found a parser bug: it refused Report Size > 32, and the OpenFFBoard's vendor HID-command
// reports (ID 0xA1) have 64-bit fields. HID 1.11 sets no limit; the parser now takes up to 256 bits
// (as Linux does) and the driver refuses only fields it must use that are wider than 32.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <utility>
#include <vector>

#include "fake_transport.hpp"
#include "sandpaper/runtime/usb/hid_descriptor.hpp"

namespace sandpaper::runtime::usb {
namespace {

std::vector<std::uint8_t> data_file(const char* name) {
  return testing::read_hex_file(std::filesystem::path(SANDPAPER_SOURCE_DIR) / "tests/runtime/usb/data" / name);
}

// HID PID 1.0 usage table: 0x95 is "PID Device Control Report" (the report's collection), 0x96 is
// "PID Device Control" (the collection of DC_* usages). The OpenFFBoard nests 0x96 inside 0x95; the
// SideWinder uses 0x96 alone as the report collection (which is what pid::kDeviceControlReport names).
constexpr std::uint32_t kPidDeviceControlReport = usage(kPidPage, 0x95);
constexpr std::uint32_t kPidDeviceControl = usage(kPidPage, 0x96);
constexpr std::uint32_t kOpEffectStartSolo = usage(kPidPage, 0x7A);
constexpr std::uint32_t kDcDevicePause = usage(kPidPage, 0x9B);
constexpr std::uint32_t kDcDeviceContinue = usage(kPidPage, 0x9C);
constexpr std::uint32_t kRamPoolAvailable = usage(kPidPage, 0xAC);
constexpr std::uint32_t kDeviceManagedPool = usage(kPidPage, 0xA9);
constexpr std::uint32_t kSharedParameterBlocks = usage(kPidPage, 0xAA);
constexpr std::uint32_t kTypeSpecificBlockOffset = usage(kPidPage, 0x58);
constexpr std::uint32_t kOrdinal1 = usage(kOrdinalPage, 1);
constexpr std::uint32_t kOrdinal2 = usage(kOrdinalPage, 2);

struct Expect {
  ReportType type;
  std::uint32_t report, field;
  int id, offset, size;
  std::int32_t min, max;
  bool variable;
};

void expect_fields(const HidReportDescriptor& d, std::initializer_list<Expect> expected) {
  for (const auto& e : expected) {
    SCOPED_TRACE(::testing::Message() << "report usage 0x" << std::hex << e.report << " field 0x" << e.field);
    const HidField* f = d.find(e.type, e.report, e.field);
    ASSERT_NE(f, nullptr);
    EXPECT_EQ(f->report_id, e.id);
    EXPECT_EQ(f->bit_offset, static_cast<std::uint32_t>(e.offset));
    EXPECT_EQ(f->bit_size, static_cast<std::uint32_t>(e.size));
    EXPECT_EQ(f->logical_min, e.min);
    EXPECT_EQ(f->logical_max, e.max);
    EXPECT_EQ(f->variable, e.variable);
  }
}

// ---------------------------------------------------------------------------------------------------
// OpenFFBoard, 2-axis FFB descriptor (hid_2ffb_desc)
// ---------------------------------------------------------------------------------------------------

TEST(RealDescriptor, OpenFFBoard2AxisParses) {
  const auto bytes = data_file("openffboard_2axis.hex");
  ASSERT_EQ(bytes.size(), 1215u);  // USB_HID_2FFB_REPORT_DESC_SIZE in usb_hid_ffb_desc.h
  EXPECT_NO_THROW(parse_hid_report_descriptor(bytes));
}

TEST(RealDescriptor, OpenFFBoard2AxisFieldsAreWhereTheFirmwareStructsPutThem) {
  HidReportDescriptor d;
  ASSERT_NO_THROW(d = parse_hid_report_descriptor(data_file("openffboard_2axis.hex")));
  EXPECT_TRUE(d.uses_report_ids);
  EXPECT_TRUE(d.has_pid_page());
  using enum ReportType;
  expect_fields(d, {
      // Input report 1 = reportHID_t (ffb_defs.h:102-113): id = 1 (:103), uint64_t buttons (:104),
      // int16_t X (:105) at byte 9, int16_t Y (:106) at byte 11. Range: LOGICAL -32767..32767.
      {Input, 0, kUsageX, 1, 64, 16, -32767, 32767, true},
      {Input, 0, kUsageY, 1, 80, 16, -32767, 32767, true},
      // Set Effect, HID_ID_EFFREP = 0x01 (ffb_defs.h:46), struct FFB_SetEffect_t (ffb_defs.h:159-179).
      {Output, pid::kSetEffectReport, pid::kEffectBlockIndex, 1, 0, 8, 1, 40, true},  // :162, MAX_EFFECTS 40 (:15)
      {Output, pid::kSetEffectReport, pid::kEffectType, 1, 8, 8, 1, 11, false},       // :163 (FFB_EFFECT_* 1..11)
      {Output, pid::kSetEffectReport, pid::kDuration, 1, 16, 16, 0, 32767, true},     // :164 uint16 ms
      {Output, pid::kSetEffectReport, pid::kTriggerRepeatInterval, 1, 32, 16, 0, 32767, true},  // :165
      {Output, pid::kSetEffectReport, pid::kSamplePeriod, 1, 48, 16, 0, 32767, true},  // :166
      {Output, pid::kSetEffectReport, pid::kStartDelay, 1, 64, 16, 0, 32767, true},    // :167
      {Output, pid::kSetEffectReport, pid::kGain, 1, 80, 8, 0, 255, true},             // :168 uint8 0..255
      {Output, pid::kSetEffectReport, pid::kTriggerButton, 1, 88, 8, 1, 8, true},      // :169 (unused)
      // enableAxis (:170) "bits: 0=X, 1=Y, 2=DirectionEnable"; HID_DIRECTION_ENABLE 0x04 (:93)
      {Output, pid::kSetEffectReport, kUsageX, 1, 96, 1, 0, 1, true},
      {Output, pid::kSetEffectReport, kUsageY, 1, 97, 1, 0, 1, true},
      {Output, pid::kSetEffectReport, pid::kDirectionEnable, 1, 98, 1, 0, 1, true},
      // directionX / directionY uint16 "angle (0=0 .. 36000=360deg)" (:171, :172)
      {Output, pid::kSetEffectReport, kOrdinal1, 1, 104, 16, 0, 36000, true},
      {Output, pid::kSetEffectReport, kOrdinal2, 1, 120, 16, 0, 36000, true},
      // Set Constant Force, HID_ID_CONSTREP = 0x05 (ffb_defs.h:50), FFB_SetConstantForce_Data_t (:300-305):
      // effectBlockIndex (:303), int16_t magnitude (:304). The descriptor's minimum is 0x8000 = -32768.
      {Output, pid::kSetConstantForceReport, pid::kEffectBlockIndex, 5, 0, 8, 1, 40, true},
      {Output, pid::kSetConstantForceReport, pid::kMagnitude, 5, 8, 16, -32768, 32767, true},
      // Effect Operation, HID_ID_EFOPREP = 0x0A (ffb_defs.h:54), FFB_EffOp_Data_t (:262-268):
      // effectBlockIndex (:265), state (:266), loopCount (:267).
      {Output, pid::kEffectOperationReport, pid::kEffectBlockIndex, 10, 0, 8, 1, 40, true},
      {Output, pid::kEffectOperationReport, pid::kEffectOperation, 10, 8, 8, 1, 3, false},
      {Output, pid::kEffectOperationReport, pid::kLoopCount, 10, 16, 8, 0, 255, true},
      // Block Free, HID_ID_BLKFRREP = 0x0B (ffb_defs.h:55); HidFFB.cpp:130-132 frees report[1]-1.
      {Output, pid::kBlockFreeReport, pid::kEffectBlockIndex, 11, 0, 8, 1, 40, true},
      // Create New Effect (feature SET), HID_ID_NEWEFREP = 0x11 (ffb_defs.h:60),
      // FFB_CreateNewEffect_Feature_Data_t (:195-200) without the ID byte ("ID removed by tinyusb", :197):
      // effectType (:198) at byte 0, uint16_t byteCount (:199) at byte 1 (10 bits + 6 padding here).
      {Feature, pid::kCreateNewEffectReport, pid::kEffectType, 17, 0, 8, 1, 11, false},
      {Feature, pid::kCreateNewEffectReport, pid::kByteCount, 17, 8, 10, 0, 511, true},
      // Block Load (feature GET), HID_ID_BLKLDREP = 0x12 (ffb_defs.h:61), FFB_BlockLoad_Feature_Data_t
      // (:203-209), ID added by tinyusb: effectBlockIndex (:206), loadStatus "1=Success,2=Full,3=Error" (:207).
      {Feature, pid::kBlockLoadReport, pid::kEffectBlockIndex, 18, 0, 8, 1, 40, true},
      {Feature, pid::kBlockLoadReport, pid::kBlockLoadStatus, 18, 8, 8, 1, 3, false},
      // PID Pool (feature GET), HID_ID_POOLREP = 0x13 (ffb_defs.h:62), FFB_PIDPool_Feature_Data_t
      // (:211-217): uint16_t ramPoolSize (:214), uint8_t maxSimultaneousEffects (:215),
      // memoryManagement (:216) bit 0 = Device Managed Pool, bit 1 = Shared Parameter Blocks.
      {Feature, pid::kPoolReport, pid::kRamPoolSize, 19, 0, 16, 0, 65535, true},
      {Feature, pid::kPoolReport, pid::kSimultaneousEffectsMax, 19, 16, 8, 0, 255, true},
      {Feature, pid::kPoolReport, kDeviceManagedPool, 19, 24, 1, 0, 1, true},
      {Feature, pid::kPoolReport, kSharedParameterBlocks, 19, 25, 1, 0, 1, true},
  });
  // Report sizes, report ID byte included.
  EXPECT_EQ(d.report_bytes(Input, 1), 25u);   // sizeof(reportHID_t) = 1 + 8 + 8 * 2
  EXPECT_EQ(d.report_bytes(Output, 5), 4u);   // sizeof(FFB_SetConstantForce_Data_t)
  EXPECT_EQ(d.report_bytes(Output, 10), 4u);  // sizeof(FFB_EffOp_Data_t)
  EXPECT_EQ(d.report_bytes(Output, 11), 2u);  // report[0] = ID, report[1] = block index
  EXPECT_EQ(d.report_bytes(Output, 12), 2u);  // report[0] = ID, report[1] = control bits (HidFFB.cpp:98)
  EXPECT_EQ(d.report_bytes(Feature, 17), 4u);  // ID + sizeof(FFB_CreateNewEffect_Feature_Data_t) = 1 + 3
  EXPECT_EQ(d.report_bytes(Feature, 18), 5u);  // ID + sizeof(FFB_BlockLoad_Feature_Data_t) = 1 + 4
  EXPECT_EQ(d.report_bytes(Feature, 19), 5u);  // ID + sizeof(FFB_PIDPool_Feature_Data_t) = 1 + 4
  // Set Effect is 22 bytes on the wire (the descriptor adds a 2 x 16-bit Type Specific Block Offset after
  // the direction); the firmware copies min(sizeof(FFB_SetEffect_t) = 18, bufsize) (HidFFB.cpp:93).
  EXPECT_EQ(d.report_bytes(Output, 1), 22u);
}

TEST(RealDescriptor, OpenFFBoard2AxisArrayValuesAreTheFirmwareCodes) {
  HidReportDescriptor d;
  ASSERT_NO_THROW(d = parse_hid_report_descriptor(data_file("openffboard_2axis.hex")));
  using enum ReportType;
  // Effect type value = FFB_EFFECT_CONSTANT (ffb_defs.h:73) in Set Effect and Create New Effect.
  for (const std::uint32_t report : {pid::kSetEffectReport, pid::kCreateNewEffectReport}) {
    const HidField* type = d.find(report == pid::kSetEffectReport ? Output : Feature, report, pid::kEffectType);
    ASSERT_NE(type, nullptr);
    EXPECT_EQ(type->array_value(pid::kEtConstantForce), 1);
  }
  // Effect Operation state: HidFFB.cpp:389 (3 = stop), :398 (2 = start solo), otherwise start.
  const HidField* op = d.find(Output, pid::kEffectOperationReport, pid::kEffectOperation);
  ASSERT_NE(op, nullptr);
  EXPECT_EQ(op->array_value(pid::kOpEffectStart), 1);
  EXPECT_EQ(op->array_value(kOpEffectStartSolo), 2);
  EXPECT_EQ(op->array_value(pid::kOpEffectStop), 3);
  // Block Load status: "1=Success,2=Full,3=Error" (ffb_defs.h:207).
  const HidField* status = d.find(Feature, pid::kBlockLoadReport, pid::kBlockLoadStatus);
  ASSERT_NE(status, nullptr);
  EXPECT_EQ(status->array_value(pid::kBlockLoadSuccess), 1);
  EXPECT_EQ(status->array_value(pid::kBlockLoadFull), 2);
  EXPECT_EQ(status->array_value(pid::kBlockLoadError), 3);
  // RAM Pool Available (ramPoolAvailable, ffb_defs.h:208) is declared as a Feature ARRAY item of 16 bits
  // at bit 16: the parser files it under its collection usage (Block Load), not under 0xAC.
  EXPECT_EQ(d.find(Feature, pid::kBlockLoadReport, kRamPoolAvailable), nullptr);
  const HidField* pool_available = d.find(Feature, pid::kBlockLoadReport, pid::kBlockLoadReport);
  ASSERT_NE(pool_available, nullptr);
  EXPECT_EQ(pool_available->bit_offset, 16u);
  EXPECT_EQ(pool_available->bit_size, 16u);
  EXPECT_FALSE(pool_available->variable);
}

TEST(RealDescriptor, OpenFFBoardDeviceControlIsABitfieldInReport0x95) {
  // HidFFB.cpp:97-98: case HID_ID_CTRLREP (0x0C, ffb_defs.h:56): ffb_control(report[1]); HidFFB.cpp:207-221:
  // bit 0x01 enable, 0x02 disable, 0x04 stop all, 0x08 reset, 0x10 pause, 0x20 continue. The descriptor
  // declares 8 one-bit Variable fields (DC usages 0x97..0x9C on bits 0..5) in collection 0x96 inside the
  // report collection 0x95, not one 8-bit array in a 0x96 report as the driver expects.
  HidReportDescriptor d;
  ASSERT_NO_THROW(d = parse_hid_report_descriptor(data_file("openffboard_2axis.hex")));
  using enum ReportType;
  const std::pair<std::uint32_t, int> bits[] = {
      {pid::kDcEnableActuators, 0}, {pid::kDcDisableActuators, 1}, {pid::kDcStopAllEffects, 2},
      {pid::kDcDeviceReset, 3},     {kDcDevicePause, 4},            {kDcDeviceContinue, 5}};
  for (const auto& [u, bit] : bits) {
    SCOPED_TRACE(::testing::Message() << "usage 0x" << std::hex << u);
    const HidField* f = d.find(Output, kPidDeviceControlReport, u);
    ASSERT_NE(f, nullptr);
    EXPECT_EQ(f->report_id, 12);
    EXPECT_EQ(f->bit_offset, static_cast<std::uint32_t>(bit));
    EXPECT_EQ(f->bit_size, 1u);
    EXPECT_TRUE(f->variable);
    EXPECT_EQ(f->parent_usage, kPidDeviceControl);
  }
  // What the driver looks up today (report usage 0x96, field usage 0x96) is not in this descriptor.
  EXPECT_EQ(d.find(Output, kPidDeviceControl, kPidDeviceControl), nullptr);
}

TEST(RealDescriptor, OpenFFBoardSetEffectOrdinalsAppearTwice) {
  // Ordinal 1 and 2 name both the Direction (0x57) and the Type Specific Block Offset (0x58) fields of Set
  // Effect: a lookup by usage alone must also check parent_usage.
  HidReportDescriptor d;
  ASSERT_NO_THROW(d = parse_hid_report_descriptor(data_file("openffboard_2axis.hex")));
  const auto ordinal1 = d.find_all(ReportType::Output, pid::kSetEffectReport, kOrdinal1);
  ASSERT_EQ(ordinal1.size(), 2u);
  EXPECT_EQ(ordinal1[0]->parent_usage, pid::kDirection);
  EXPECT_EQ(ordinal1[0]->bit_offset, 104u);
  EXPECT_EQ(ordinal1[1]->parent_usage, kTypeSpecificBlockOffset);
  EXPECT_EQ(ordinal1[1]->bit_offset, 136u);
  EXPECT_EQ(ordinal1[1]->logical_max, 32765);
}

// ---------------------------------------------------------------------------------------------------
// OpenFFBoard, 1-axis FFB wheel descriptor (hid_1ffb_desc): same reports, one force axis.
// ---------------------------------------------------------------------------------------------------

TEST(RealDescriptor, OpenFFBoard1AxisWheelHasOneForceAxis) {
  const auto bytes = data_file("openffboard_1axis_wheel.hex");
  ASSERT_EQ(bytes.size(), 1196u);  // USB_HID_1FFB_REPORT_DESC_SIZE
  HidReportDescriptor d;
  ASSERT_NO_THROW(d = parse_hid_report_descriptor(bytes));
  using enum ReportType;
  // Position report as in the 2-axis descriptor (X and Y are both reported).
  expect_fields(d, {
      {Input, 0, kUsageX, 1, 64, 16, -32767, 32767, true},
      {Input, 0, kUsageY, 1, 80, 16, -32767, 32767, true},
      {Output, pid::kSetConstantForceReport, pid::kMagnitude, 5, 8, 16, -32768, 32767, true},
      // Axes Enable X and Direction Enable are declared with Logical Maximum 0 (the Direction Enable item
      // inherits it): a host that honours logical ranges cannot set either bit to 1.
      {Output, pid::kSetEffectReport, kUsageX, 1, 96, 1, 0, 0, true},
      {Output, pid::kSetEffectReport, pid::kDirectionEnable, 1, 97, 1, 0, 0, true},
      {Output, pid::kSetEffectReport, kOrdinal1, 1, 104, 16, 0, 36000, true},
  });
  // What it lacks for a 2-axis joystick: no Y in Axes Enable, no second direction ordinal.
  EXPECT_EQ(d.find(Output, pid::kSetEffectReport, kUsageY), nullptr);
  for (const HidField* f : d.find_all(Output, pid::kSetEffectReport, kOrdinal2)) ADD_FAILURE() << "Ordinal 2 at bit " << f->bit_offset;
  EXPECT_EQ(d.report_bytes(Output, 1), 18u);
}

// ---------------------------------------------------------------------------------------------------
// Microsoft SideWinder Force Feedback 2, recorded descriptor. Expected values are the recorded items
// (see the decoded listing in the same SidewinderFFPDetails.md).
// ---------------------------------------------------------------------------------------------------

TEST(RealDescriptor, SideWinderForceFeedback2HasEveryReportTheDriverNeeds) {
  const auto bytes = data_file("ms_sidewinder_ffb2.hex");
  ASSERT_EQ(bytes.size(), 1343u);  // wDescriptorLength of the recorded HID descriptor
  HidReportDescriptor d;
  ASSERT_NO_THROW(d = parse_hid_report_descriptor(bytes));
  EXPECT_TRUE(d.uses_report_ids);
  EXPECT_TRUE(d.has_pid_page());
  using enum ReportType;
  expect_fields(d, {
      // Input report 1: X, 6 bits padding, Y, 6 bits padding (10-bit axes, -512..511).
      {Input, 0, kUsageX, 1, 0, 10, -512, 511, true},
      {Input, 0, kUsageY, 1, 16, 10, -512, 511, true},
      {Output, pid::kSetEffectReport, pid::kEffectBlockIndex, 1, 0, 8, 1, 40, true},
      {Output, pid::kSetEffectReport, pid::kEffectType, 1, 8, 8, 1, 12, false},
      {Output, pid::kSetEffectReport, pid::kDuration, 1, 16, 16, 0, 32767, true},
      {Output, pid::kSetEffectReport, pid::kGain, 1, 64, 8, 0, 255, true},
      {Output, pid::kSetEffectReport, kUsageX, 1, 80, 1, 0, 1, true},
      {Output, pid::kSetEffectReport, kUsageY, 1, 81, 1, 0, 1, true},
      {Output, pid::kSetEffectReport, pid::kDirectionEnable, 1, 82, 1, 0, 1, true},
      {Output, pid::kSetEffectReport, kOrdinal1, 1, 88, 8, 0, 255, true},  // 8-bit direction
      {Output, pid::kSetEffectReport, kOrdinal2, 1, 96, 8, 0, 255, true},
      {Output, pid::kSetEffectReport, pid::kStartDelay, 1, 104, 16, 0, 32767, true},
      {Output, pid::kSetConstantForceReport, pid::kEffectBlockIndex, 5, 0, 8, 1, 40, true},
      {Output, pid::kSetConstantForceReport, pid::kMagnitude, 5, 8, 16, -255, 255, true},
      {Output, pid::kEffectOperationReport, pid::kEffectBlockIndex, 10, 0, 8, 1, 40, true},
      {Output, pid::kEffectOperationReport, pid::kEffectOperation, 10, 8, 8, 1, 3, false},
      {Output, pid::kBlockFreeReport, pid::kEffectBlockIndex, 11, 0, 8, 1, 40, true},
      // Device Control: report collection 0x96 with one 8-bit Array field 1..6 (the form the driver uses).
      {Output, kPidDeviceControl, kPidDeviceControl, 12, 0, 8, 1, 6, false},
      // Feature report IDs 1, 2, 3 (the same numbers as output reports: IDs are per report type).
      {Feature, pid::kCreateNewEffectReport, pid::kEffectType, 1, 0, 8, 1, 12, false},
      {Feature, pid::kCreateNewEffectReport, pid::kByteCount, 1, 8, 10, 0, 511, true},
      {Feature, pid::kBlockLoadReport, pid::kEffectBlockIndex, 2, 0, 8, 1, 40, true},
      {Feature, pid::kBlockLoadReport, pid::kBlockLoadStatus, 2, 8, 8, 1, 3, false},
      {Feature, pid::kPoolReport, pid::kRamPoolSize, 3, 0, 16, 0, 65535, true},
      {Feature, pid::kPoolReport, pid::kSimultaneousEffectsMax, 3, 16, 8, 0, 255, true},
  });
  const HidField* control = d.find(Output, kPidDeviceControl, kPidDeviceControl);
  ASSERT_NE(control, nullptr);
  EXPECT_EQ(control->array_value(pid::kDcEnableActuators), 1);
  EXPECT_EQ(control->array_value(pid::kDcStopAllEffects), 3);
  EXPECT_EQ(control->array_value(pid::kDcDeviceReset), 4);
  EXPECT_EQ(d.find(Feature, pid::kCreateNewEffectReport, pid::kEffectType)->array_value(pid::kEtConstantForce), 1);
  EXPECT_EQ(d.find(Feature, pid::kBlockLoadReport, pid::kBlockLoadStatus)->array_value(pid::kBlockLoadSuccess), 1);
  EXPECT_EQ(d.report_bytes(Input, 1), 13u);
  EXPECT_EQ(d.report_bytes(Output, 1), 16u);
  EXPECT_EQ(d.report_bytes(Output, 5), 4u);
  EXPECT_EQ(d.report_bytes(Feature, 1), 4u);
  EXPECT_EQ(d.report_bytes(Feature, 2), 5u);
}

}  // namespace
}  // namespace sandpaper::runtime::usb
