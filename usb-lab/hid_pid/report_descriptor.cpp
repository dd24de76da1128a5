// HID 1.11 section 6.2.2: a report descriptor is a sequence of items; main items (Input, Output,
// Feature, Collection, End Collection) make fields and collections from the global state (kept
// across main items, saved and restored by Push/Pop) and the local state (cleared after each
// main item).
#include "report_descriptor.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace sandpaper::usb_lab::hid {
namespace {

// Item types and tags (HID 1.11 sections 6.2.2.4, 6.2.2.7, 6.2.2.8).
enum : std::uint8_t { kMain = 0, kGlobal = 1, kLocal = 2, kReserved = 3 };
enum : std::uint8_t { kInput = 0x8, kOutput = 0x9, kCollection = 0xA, kFeature = 0xB, kEndCollection = 0xC };
enum : std::uint8_t {
  kUsagePage = 0x0, kLogicalMin = 0x1, kLogicalMax = 0x2, kPhysicalMin = 0x3, kPhysicalMax = 0x4, kUnitExponent = 0x5,
  kReportSize = 0x7, kReportId = 0x8, kReportCount = 0x9,
  kPush = 0xA, kPop = 0xB
};
enum : std::uint8_t { kUsage = 0x0, kUsageMin = 0x1, kUsageMax = 0x2 };

constexpr std::uint8_t kLongItem = 0xFE;             // HID 1.11 section 6.2.2.3
constexpr std::size_t kMaxRangeUsages = 0x10000;      // one usage page's worth
constexpr std::uint64_t kMaxReportBits = 65535 * 8;   // wLength of GET_REPORT bounds any report

[[noreturn]] void fail(std::size_t offset, const std::string& what) {
  throw std::invalid_argument("HID report descriptor, byte " + std::to_string(offset) + ": " + what);
}

// An item's data as unsigned and as signed (two's complement of its size), HID 1.11 section 5.8.
struct ItemData {
  std::uint32_t u = 0;
  std::int32_t s = 0;
  std::size_t size = 0;
};

// The global items that make a field (HID 1.11 section 6.2.2.7). Logical Maximum is kept as its
// item's data: whether its top bit is a sign depends on Logical Minimum (resolve_max).
struct Globals {
  std::uint16_t usage_page = 0;
  std::int32_t logical_min = 0;
  ItemData logical_max;
  std::int32_t physical_min = 0;
  ItemData physical_max;
  int unit_exponent = 0;
  std::uint32_t report_size = 0, report_count = 0;
  std::uint8_t report_id = 0;
};

// A local Usage or Usage Minimum/Maximum: a 1- or 2-byte one takes the Usage Page in effect at the
// main item that uses it; a 4-byte one is an extended usage, page included (section 6.2.2.8).
struct LocalUsage {
  std::uint32_t value = 0;
  bool extended = false;
  std::uint32_t resolve(std::uint16_t page) const { return extended ? value : usage(page, static_cast<std::uint16_t>(value)); }
};

struct Locals {
  std::vector<LocalUsage> usages;
  std::optional<LocalUsage> usage_min, usage_max;
  std::size_t range_offset = 0;
};

// Logical Maximum is signed when Logical Minimum is negative (the pair is then a signed range),
// else unsigned: 0x26 FF 00 after Logical Minimum 0 is 255, after Logical Minimum -255 it is 255
// too, and 0x25 FF is 255 after 0 but -1 after -128.
// Physical Maximum follows Physical Minimum the same way.
std::int32_t resolve_max(std::int32_t min, const ItemData& max) {
  if (min < 0) return max.s;
  return static_cast<std::int32_t>(std::min<std::uint32_t>(max.u, 0x7FFFFFFF));
}

// The local usages in order, a Usage Minimum..Maximum range expanded in place of where it ended
// (section 6.2.2.8: the range stands for the usages between, inclusive).
std::vector<std::uint32_t> usage_list(const Locals& l, std::uint16_t page) {
  std::vector<std::uint32_t> out;
  for (const LocalUsage& u : l.usages) out.push_back(u.resolve(page));
  if (l.usage_min || l.usage_max) {
    if (!(l.usage_min && l.usage_max)) fail(l.range_offset, "Usage Minimum without Usage Maximum (or the reverse)");
    const std::uint32_t lo = l.usage_min->resolve(page), hi = l.usage_max->resolve(page);
    if (hi < lo) fail(l.range_offset, "Usage Maximum below Usage Minimum");
    if (hi - lo >= kMaxRangeUsages) fail(l.range_offset, "a usage range of more than 65536 usages");
    for (std::uint32_t u = lo;; ++u) {
      out.push_back(u);
      if (u == hi) break;
    }
  }
  return out;
}

}  // namespace

std::uint32_t ReportField::element_usage(std::size_t i) const {
  if (usages.empty()) return 0;
  return usages[std::min(i, usages.size() - 1)];
}

std::optional<std::uint32_t> ReportField::array_usage(std::int64_t value) const {
  const std::int64_t index = value - logical_min;
  if (value < logical_min || value > logical_max || index >= static_cast<std::int64_t>(usages.size())) return std::nullopt;
  return usages[static_cast<std::size_t>(index)];
}

std::optional<std::int32_t> ReportField::array_value(std::uint32_t u) const {
  const auto at = std::find(usages.begin(), usages.end(), u);
  if (at == usages.end()) return std::nullopt;
  const auto value = static_cast<std::int64_t>(logical_min) + (at - usages.begin());
  if (value > logical_max) return std::nullopt;
  return static_cast<std::int32_t>(value);
}

double ReportField::physical(std::int64_t logical) const {
  double p = static_cast<double>(logical);
  if ((physical_min != 0 || physical_max != 0) && logical_max != logical_min)
    p = physical_min + (p - logical_min) * (static_cast<double>(physical_max) - physical_min) /
                           (static_cast<double>(logical_max) - logical_min);
  return p * std::pow(10.0, unit_exponent);
}

std::size_t ReportDescriptor::report_bytes(ReportType type, std::uint8_t report_id) const {
  std::uint64_t bits = 0;
  bool any = false;
  for (const ReportField& f : fields)
    if (f.type == type && f.report_id == report_id) {
      any = true;
      bits = std::max<std::uint64_t>(bits, std::uint64_t{f.bit_offset} + std::uint64_t{f.bit_size} * f.count);
    }
  if (!any) return 0;
  return static_cast<std::size_t>((bits + 7) / 8) + (uses_report_ids ? 1 : 0);
}

std::vector<std::uint8_t> ReportDescriptor::report_ids(ReportType type) const {
  std::set<std::uint8_t> ids;
  for (const ReportField& f : fields)
    if (f.type == type) ids.insert(f.report_id);
  return {ids.begin(), ids.end()};
}

// Item grammar (HID 1.11 sections 6.2.2.2, 6.2.2.3):
//   short item = prefix [data]; prefix = bTag(4) bType(2) bSize(2), data 0, 1, 2 or 4 bytes
//                (bSize 3 means 4), little-endian;
//   long item  = 0xFE bDataSize bLongItemTag data[bDataSize] (no tag is defined: skipped).
// Main items (6.2.2.4-6.2.2.6): Input/Output/Feature append Report Count x Report Size bits to the
// report (type, Report ID) at that report's running bit offset; Collection opens a collection whose
// usage is the first local usage; End Collection closes one. After every main item the local
// state is cleared (6.2.2.8). Global items (6.2.2.7) persist; Push saves them, Pop restores.
ReportDescriptor parse_report_descriptor(std::span<const std::uint8_t> bytes) {
  ReportDescriptor out;
  Globals g;
  std::vector<Globals> pushed;
  Locals l;
  std::vector<std::uint32_t> collections;  // outermost first while parsing
  std::vector<std::size_t> collection_offsets;
  std::map<std::pair<ReportType, std::uint8_t>, std::uint64_t> next_bit;

  std::size_t at = 0;
  while (at < bytes.size()) {
    const std::size_t item = at;
    const std::uint8_t prefix = bytes[at++];
    if (prefix == kLongItem) {
      if (at + 2 > bytes.size()) fail(item, "long item truncated");
      const std::size_t size = bytes[at];
      at += 2;
      if (at + size > bytes.size()) fail(item, "long item's data truncated");
      at += size;
      continue;
    }
    const std::size_t size = (prefix & 3) == 3 ? 4 : (prefix & 3);
    const std::uint8_t type = (prefix >> 2) & 3, tag = prefix >> 4;
    if (at + size > bytes.size()) fail(item, "item truncated (" + std::to_string(size) + " data bytes declared)");
    ItemData d;
    d.size = size;
    for (std::size_t i = 0; i < size; ++i) d.u |= std::uint32_t{bytes[at + i]} << (8 * i);
    if (size > 0 && size < 4 && (d.u >> (8 * size - 1)) & 1) d.s = static_cast<std::int32_t>(d.u | (~0u << (8 * size)));
    else d.s = static_cast<std::int32_t>(d.u);
    at += size;

    switch (type) {
      case kMain:
        switch (tag) {
          case kInput:
          case kOutput:
          case kFeature: {
            ReportField f;
            f.type = tag == kInput ? ReportType::Input : tag == kOutput ? ReportType::Output : ReportType::Feature;
            f.report_id = g.report_id;
            f.bit_size = g.report_size;
            f.count = g.report_count;
            f.logical_min = g.logical_min;
            f.logical_max = resolve_max(g.logical_min, g.logical_max);
            f.physical_min = g.physical_min;
            f.physical_max = resolve_max(g.physical_min, g.physical_max);
            f.unit_exponent = g.unit_exponent;
            f.constant = d.u & 0x01;
            f.variable = d.u & 0x02;
            f.null_state = d.u & 0x40;
            f.usages = usage_list(l, g.usage_page);
            f.collections.assign(collections.rbegin(), collections.rend());
            std::uint64_t& bit = next_bit[{f.type, f.report_id}];
            f.bit_offset = static_cast<std::uint32_t>(bit);
            bit += std::uint64_t{f.bit_size} * f.count;
            if (bit > kMaxReportBits) fail(item, "the report grows past 65535 bytes");
            out.fields.push_back(std::move(f));
            break;
          }
          case kCollection: {
            const std::vector<std::uint32_t> u = usage_list(l, g.usage_page);
            collections.push_back(u.empty() ? 0 : u.front());
            collection_offsets.push_back(item);
            break;
          }
          case kEndCollection:
            if (collections.empty()) fail(item, "End Collection without a Collection");
            collections.pop_back();
            collection_offsets.pop_back();
            break;
          default:
            fail(item, "reserved main item tag " + std::to_string(tag));
        }
        l = Locals{};
        break;
      case kGlobal:
        switch (tag) {
          case kUsagePage: g.usage_page = static_cast<std::uint16_t>(d.u); break;
          case kLogicalMin: g.logical_min = d.s; break;
          case kLogicalMax: g.logical_max = d; break;
          case kPhysicalMin: g.physical_min = d.s; break;
          case kPhysicalMax: g.physical_max = d; break;
          // A 4-bit signed exponent (0xD is -3); descriptors write it as a signed byte too (0xFD),
          // whose low nibble is the same number.
          case kUnitExponent: g.unit_exponent = static_cast<int>(d.u & 0x7) - static_cast<int>(d.u & 0x8); break;
          case kReportSize: g.report_size = d.u; break;
          case kReportCount: g.report_count = d.u; break;
          case kReportId:
            if (d.u == 0 || d.u > 255) fail(item, "Report ID " + std::to_string(d.u) + " (1..255 allowed)");
            g.report_id = static_cast<std::uint8_t>(d.u);
            out.uses_report_ids = true;
            break;
          case kPush: pushed.push_back(g); break;
          case kPop:
            if (pushed.empty()) fail(item, "Pop without Push");
            g = pushed.back();
            pushed.pop_back();
            break;
          default: break;  // Unit: the model knows each usage's unit from the PID specification
        }
        break;
      case kLocal:
        switch (tag) {
          case kUsage: l.usages.push_back(LocalUsage{d.u, size == 4}); break;
          case kUsageMin: l.usage_min = LocalUsage{d.u, size == 4}; l.range_offset = item; break;
          case kUsageMax: l.usage_max = LocalUsage{d.u, size == 4}; l.range_offset = item; break;
          default: break;  // designators, strings, delimiters: not needed
        }
        break;
      default:
        fail(item, "reserved item type (prefix " + std::to_string(prefix) + ")");
    }
  }
  if (!collections.empty()) fail(collection_offsets.back(), "Collection never ended");
  return out;
}

std::int64_t read_field(std::span<const std::uint8_t> data, const ReportField& field, std::size_t element) {
  const std::uint32_t bits = std::min<std::uint32_t>(field.bit_size, 32);
  const std::uint64_t first = std::uint64_t{field.bit_offset} + std::uint64_t{field.bit_size} * element;
  std::uint64_t v = 0;
  for (std::uint32_t i = 0; i < bits; ++i) {
    const std::uint64_t bit = first + i;
    if (bit / 8 < data.size() && (data[bit / 8] >> (bit % 8)) & 1) v |= std::uint64_t{1} << i;
  }
  if (field.logical_min < 0 && bits > 0 && (v >> (bits - 1)) & 1) return static_cast<std::int64_t>(v) - (std::int64_t{1} << bits);
  return static_cast<std::int64_t>(v);
}

void write_field(std::span<std::uint8_t> data, const ReportField& field, std::int64_t value, std::size_t element) {
  const std::uint64_t first = std::uint64_t{field.bit_offset} + std::uint64_t{field.bit_size} * element;
  const auto v = static_cast<std::uint64_t>(value);
  for (std::uint32_t i = 0; i < field.bit_size; ++i) {
    const std::uint64_t bit = first + i;
    if (bit / 8 >= data.size()) return;
    const auto mask = static_cast<std::uint8_t>(1u << (bit % 8));
    const bool set = i < 64 && (v >> i) & 1;
    data[bit / 8] = static_cast<std::uint8_t>(set ? data[bit / 8] | mask : data[bit / 8] & ~mask);
  }
}

}  // namespace sandpaper::usb_lab::hid
