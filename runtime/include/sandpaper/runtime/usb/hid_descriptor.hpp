#pragma once
// HID report descriptor parsing (USB HID 1.11 section 6.2.2): the fields of every input, output and
// feature report with their report ID, bit offset, size and logical range, and the usages that name
// them. Enough for a joystick's X/Y axes (Generic Desktop page) and the force-feedback reports of the
// Physical Interface Device page (USB HID PID 1.0), which is what hid_pid_joystick.hpp needs.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace sandpaper::runtime::usb {

// Usage pages and usages, (page << 16) | id as HID extended usages are written.
constexpr std::uint32_t usage(std::uint16_t page, std::uint16_t id) { return (std::uint32_t{page} << 16) | id; }
inline constexpr std::uint16_t kGenericDesktopPage = 0x01;
inline constexpr std::uint16_t kOrdinalPage = 0x0A;
inline constexpr std::uint16_t kPidPage = 0x0F;   // Physical Interface Device, HID PID 1.0 section 5

// HID PID 1.0 usages used by the driver (section 5, Table 1 onward).
namespace pid {
inline constexpr std::uint32_t kSetEffectReport = usage(kPidPage, 0x21);
inline constexpr std::uint32_t kEffectBlockIndex = usage(kPidPage, 0x22);
inline constexpr std::uint32_t kEffectType = usage(kPidPage, 0x25);
inline constexpr std::uint32_t kEtConstantForce = usage(kPidPage, 0x26);
inline constexpr std::uint32_t kDuration = usage(kPidPage, 0x50);
inline constexpr std::uint32_t kSamplePeriod = usage(kPidPage, 0x51);
inline constexpr std::uint32_t kGain = usage(kPidPage, 0x52);
inline constexpr std::uint32_t kTriggerButton = usage(kPidPage, 0x53);
inline constexpr std::uint32_t kTriggerRepeatInterval = usage(kPidPage, 0x54);
inline constexpr std::uint32_t kAxesEnable = usage(kPidPage, 0x55);
inline constexpr std::uint32_t kDirectionEnable = usage(kPidPage, 0x56);
inline constexpr std::uint32_t kDirection = usage(kPidPage, 0x57);
inline constexpr std::uint32_t kMagnitude = usage(kPidPage, 0x70);
inline constexpr std::uint32_t kSetConstantForceReport = usage(kPidPage, 0x73);
inline constexpr std::uint32_t kEffectOperationReport = usage(kPidPage, 0x77);
inline constexpr std::uint32_t kEffectOperation = usage(kPidPage, 0x78);
inline constexpr std::uint32_t kOpEffectStart = usage(kPidPage, 0x79);
inline constexpr std::uint32_t kOpEffectStop = usage(kPidPage, 0x7B);
inline constexpr std::uint32_t kLoopCount = usage(kPidPage, 0x7C);
inline constexpr std::uint32_t kPoolReport = usage(kPidPage, 0x7F);
inline constexpr std::uint32_t kRamPoolSize = usage(kPidPage, 0x80);
inline constexpr std::uint32_t kSimultaneousEffectsMax = usage(kPidPage, 0x83);
inline constexpr std::uint32_t kBlockLoadReport = usage(kPidPage, 0x89);
inline constexpr std::uint32_t kBlockLoadStatus = usage(kPidPage, 0x8B);
inline constexpr std::uint32_t kBlockLoadSuccess = usage(kPidPage, 0x8C);
inline constexpr std::uint32_t kBlockLoadFull = usage(kPidPage, 0x8D);
inline constexpr std::uint32_t kBlockLoadError = usage(kPidPage, 0x8E);
inline constexpr std::uint32_t kBlockFreeReport = usage(kPidPage, 0x90);
// "PID Device Control" (0x96): the report collection when Device Control is one array field (the
// SideWinder Force Feedback 2); "PID Device Control Report" (0x95): the report collection around
// one 1-bit variable per command, read as a bitmask (the OpenFFBoard). The driver speaks both.
inline constexpr std::uint32_t kDeviceControlReport = usage(kPidPage, 0x96);
inline constexpr std::uint32_t kDeviceControlBitsReport = usage(kPidPage, 0x95);
inline constexpr std::uint32_t kDcEnableActuators = usage(kPidPage, 0x97);
inline constexpr std::uint32_t kDcDisableActuators = usage(kPidPage, 0x98);
inline constexpr std::uint32_t kDcStopAllEffects = usage(kPidPage, 0x99);
inline constexpr std::uint32_t kDcDeviceReset = usage(kPidPage, 0x9A);
inline constexpr std::uint32_t kCreateNewEffectReport = usage(kPidPage, 0xAB);
inline constexpr std::uint32_t kStartDelay = usage(kPidPage, 0xA7);
inline constexpr std::uint32_t kByteCount = usage(kGenericDesktopPage, 0x3B);  // Create New Effect's size field
}  // namespace pid
inline constexpr std::uint32_t kUsageX = usage(kGenericDesktopPage, 0x30);
inline constexpr std::uint32_t kUsageY = usage(kGenericDesktopPage, 0x31);

enum class ReportType { Input, Output, Feature };

// One element of a report: a variable item's value for one usage, or one slot of an array item.
// Bit offsets count from the first bit after the report ID byte (or from bit 0 when the descriptor
// uses no report IDs); report bytes are little-endian, least significant bit first (HID 1.11 5.8).
struct HidField {
  ReportType type = ReportType::Input;
  std::uint8_t report_id = 0;          // 0: the descriptor uses no report IDs
  std::uint32_t bit_offset = 0, bit_size = 0;
  std::int32_t logical_min = 0, logical_max = 0;
  bool variable = true;                // false: an array item, whose value selects one of `array_usages`
  bool constant = false;               // padding
  std::uint32_t usage = 0;             // variable items: (page << 16) | id; arrays: the enclosing collection's usage
  std::vector<std::uint32_t> array_usages;  // arrays: the usage that value logical_min + i selects
  std::uint32_t report_usage = 0;      // the outermost enclosing PID-page collection (e.g. Set Effect Report), or 0
  std::uint32_t parent_usage = 0;      // the innermost enclosing collection's usage

  // Array items: the value that selects `u`, or nullopt if `u` is not among the array's usages.
  std::optional<std::int32_t> array_value(std::uint32_t u) const;
  // Array items: the usage selected by `value`, or 0.
  std::uint32_t array_usage(std::int32_t value) const;
};

struct HidReportDescriptor {
  std::vector<HidField> fields;        // in descriptor order, padding included
  bool uses_report_ids = false;

  // The first non-constant field of a report of `type` with this report usage (0: any) and usage
  // (variables) or enclosing collection usage (arrays); nullptr if none.
  const HidField* find(ReportType type, std::uint32_t report_usage, std::uint32_t field_usage) const;
  // Every such field, in order (e.g. the two Direction ordinals of Set Effect).
  std::vector<const HidField*> find_all(ReportType type, std::uint32_t report_usage, std::uint32_t field_usage) const;
  // Size in bytes of report `id` of `type`, report ID byte included; 0 if there is no such report.
  std::size_t report_bytes(ReportType type, std::uint8_t id) const;
  // True if any usage or collection is on the PID page: the device does force feedback.
  bool has_pid_page() const;
};

// Thrown for a descriptor that cannot be parsed: an item that runs past the end, an unbalanced
// End Collection, a report size over 256 bits, Pop without Push, or a claim over the limits below.
// what() names the byte offset.
struct HidDescriptorError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What a descriptor may claim. A descriptor comes from the device (or a file standing for one): it
// is outside input, and a few bytes can claim billions of fields (docs/RELIABILITY.md, F22). The
// per-item and per-report limits are Linux hid-core's (include/linux/hid.h), so every device Linux
// drives meets them; the totals bound what is kept, far above any force-feedback joystick's.
namespace hid_limits {
inline constexpr std::size_t kDescriptorBytes = 65535;     // wDescriptorLength is 16 bits (HID 1.11 section 6.2.1)
inline constexpr std::uint32_t kUsagesPerItem = 12288;     // Report Count, and usages before a main item (HID_MAX_USAGES)
inline constexpr std::uint32_t kReportBytes = 16384;       // a report, report ID byte included (HID_MAX_BUFFER_SIZE)
inline constexpr std::size_t kFields = 65536;              // HidField entries in all (one per Report Count slot)
inline constexpr std::size_t kArrayUsages = 1u << 20;      // array usages kept in all, over every slot of every array
}  // namespace hid_limits

// Parses a report descriptor of at most hid_limits::kDescriptorBytes. Throws HidDescriptorError.
HidReportDescriptor parse_hid_report_descriptor(std::span<const std::uint8_t> bytes);

// Field values in report buffers. `report` starts with the report ID byte when `uses_ids`.
// Values are written as their low bit_size bits (two's complement for negative values).
void write_field(std::span<std::uint8_t> report, bool uses_ids, const HidField& field, std::int64_t value) noexcept;
// Sign-extends when the field's logical minimum is negative.
std::int64_t read_field(std::span<const std::uint8_t> report, bool uses_ids, const HidField& field) noexcept;

}  // namespace sandpaper::runtime::usb
