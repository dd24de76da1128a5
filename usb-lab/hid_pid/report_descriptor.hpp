#pragma once
// The USB lab's own HID report descriptor parser (HID 1.11 section 6.2.2), for the lab's HID PID
// device model. Deliberately separate from the runtime's parser (runtime/usb/hid_descriptor.hpp):
// that one is what the lab tests, so the device side must not share its mistakes.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace sandpaper::usb_lab::hid {

// Report types as GET_REPORT / SET_REPORT number them in wValue's high byte (HID 1.11 section 7.2.1).
enum class ReportType : std::uint8_t { Input = 1, Output = 2, Feature = 3 };

// A usage with its page: page << 16 | id (HID 1.11 section 6.2.2.8, "extended usage").
constexpr std::uint32_t usage(std::uint16_t page, std::uint16_t id) { return std::uint32_t{page} << 16 | id; }

// One Input, Output or Feature main item: Report Count elements of Report Size bits each.
struct ReportField {
  ReportType type = ReportType::Input;
  std::uint8_t report_id = 0;    // 0: the descriptor declares no report IDs
  std::uint32_t bit_offset = 0;  // of the first element, from the start of the report's data (after its ID byte)
  std::uint32_t bit_size = 0;    // Report Size
  std::uint32_t count = 0;       // Report Count
  std::int32_t logical_min = 0, logical_max = 0;
  // Physical Minimum/Maximum and Unit Exponent (HID 1.11 section 6.2.2.7), for values with units
  // (Direction in degrees, Duration in s): physical() converts.
  std::int32_t physical_min = 0, physical_max = 0;
  int unit_exponent = 0;
  bool constant = false;   // bit 0 of the item's data: Constant (padding), not Data
  bool variable = false;   // bit 1: Variable (one value per element); clear: Array (each element a usage index)
  bool null_state = false; // bit 6: values outside the logical range mean "no value"
  // Variable: the usage of each element in order, the last repeated for elements beyond the list
  // (HID 1.11 section 6.2.2.8). Array: the usage list an element's value indexes, value
  // logical_min naming usages[0].
  std::vector<std::uint32_t> usages;
  // The usage of each enclosing collection, innermost first (empty for an item outside any).
  std::vector<std::uint32_t> collections;

  // The usage of element `i` of a Variable field (0 when the field has no usages).
  std::uint32_t element_usage(std::size_t i) const;
  // The usage an Array element's `value` selects; nullopt when it selects none (out of range).
  std::optional<std::uint32_t> array_usage(std::int64_t value) const;
  // The value that selects `u` in an Array field; nullopt when `u` is not in its list.
  std::optional<std::int32_t> array_value(std::uint32_t u) const;
  // A logical value in the field's physical units times 10^unit_exponent (HID 1.11 section
  // 6.2.2.7: linear from the logical to the physical range; both physical bounds 0 means the
  // physical range is the logical one).
  double physical(std::int64_t logical) const;
  std::uint32_t innermost_collection() const { return collections.empty() ? 0 : collections.front(); }
};

struct ReportDescriptor {
  std::vector<ReportField> fields;  // in descriptor order
  bool uses_report_ids = false;     // a Report ID item appeared: every report starts with its ID byte

  // A report's length on the wire, in bytes: its ID byte (when the descriptor uses IDs) and its
  // fields, rounded up to whole bytes. 0 when the descriptor has no such report.
  std::size_t report_bytes(ReportType type, std::uint8_t report_id) const;
  // The report IDs of `type`, ascending, each once.
  std::vector<std::uint8_t> report_ids(ReportType type) const;
};

// Parses `bytes` as a report descriptor. Throws std::invalid_argument naming the byte offset of the
// item that is wrong (truncated, unbalanced collection or Push/Pop, Report ID 0, a bad usage
// range, a reserved item, a report longer than 65535 bytes).
ReportDescriptor parse_report_descriptor(std::span<const std::uint8_t> bytes);

// Reads element `element` of `field` from a report's data (after the ID byte), little-endian
// (HID 1.11 section 5.8), sign-extended when the field's logical minimum is negative. Bits beyond
// `data` read as 0. Fields wider than 32 bits give their low 32 bits.
std::int64_t read_field(std::span<const std::uint8_t> data, const ReportField& field, std::size_t element = 0);
// Writes the low Report Size bits of `value` into element `element` of `field` in `data`; bits
// beyond `data` are dropped.
void write_field(std::span<std::uint8_t> data, const ReportField& field, std::int64_t value, std::size_t element = 0);

}  // namespace sandpaper::usb_lab::hid
