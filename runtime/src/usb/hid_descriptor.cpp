// HID report descriptor items (HID 1.11 section 6.2.2): a prefix byte (bSize in bits 0-1, where 3
// means 4 bytes; bType in bits 2-3: 0 main, 1 global, 2 local; bTag in bits 4-7), then the data.
// 0xFE starts a long item (size byte, tag byte, data), which no standard tag uses: it is skipped.
#include "sandpaper/runtime/usb/hid_descriptor.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

namespace sandpaper::runtime::usb {
namespace {

struct Globals {
  std::uint16_t usage_page = 0;
  std::int32_t logical_min = 0, logical_max = 0;
  std::uint32_t report_size = 0, report_count = 0;
  std::uint8_t report_id = 0;
};

struct Collection {
  std::uint32_t usage = 0;
  std::uint32_t pid_report = 0;  // the outermost PID-page collection at or above this one, or 0
};

[[noreturn]] void fail(std::size_t at, const std::string& what) {
  throw HidDescriptorError("HID report descriptor, byte " + std::to_string(at) + ": " + what);
}

std::uint32_t unsigned_data(std::span<const std::uint8_t> data) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < data.size(); ++i) v |= std::uint32_t{data[i]} << (8 * i);
  return v;
}

std::int32_t signed_data(std::span<const std::uint8_t> data) {
  const std::uint32_t v = unsigned_data(data);
  switch (data.size()) {
    case 1: return static_cast<std::int8_t>(v);
    case 2: return static_cast<std::int16_t>(v);
    case 4: return static_cast<std::int32_t>(v);
    default: return 0;
  }
}

// A local usage: 4-byte data carries its own page (an extended usage), shorter data takes the
// current Usage Page.
std::uint32_t full_usage(std::span<const std::uint8_t> data, std::uint16_t page) {
  const std::uint32_t v = unsigned_data(data);
  return data.size() == 4 ? v : usage(page, static_cast<std::uint16_t>(v));
}

const char* type_name(ReportType t) {
  return t == ReportType::Input ? "input" : t == ReportType::Output ? "output" : "feature";
}

}  // namespace

std::optional<std::int32_t> HidField::array_value(std::uint32_t u) const {
  const auto it = std::find(array_usages.begin(), array_usages.end(), u);
  if (it == array_usages.end()) return std::nullopt;
  return logical_min + static_cast<std::int32_t>(it - array_usages.begin());
}

std::uint32_t HidField::array_usage(std::int32_t value) const {
  const std::int64_t i = std::int64_t{value} - logical_min;
  return i >= 0 && i < static_cast<std::int64_t>(array_usages.size()) ? array_usages[static_cast<std::size_t>(i)] : 0;
}

const HidField* HidReportDescriptor::find(ReportType type, std::uint32_t report_usage, std::uint32_t field_usage) const {
  for (const auto& f : fields)
    if (!f.constant && f.type == type && (report_usage == 0 || f.report_usage == report_usage) && f.usage == field_usage)
      return &f;
  return nullptr;
}

std::vector<const HidField*> HidReportDescriptor::find_all(ReportType type, std::uint32_t report_usage,
                                                           std::uint32_t field_usage) const {
  std::vector<const HidField*> found;
  for (const auto& f : fields)
    if (!f.constant && f.type == type && (report_usage == 0 || f.report_usage == report_usage) && f.usage == field_usage)
      found.push_back(&f);
  return found;
}

std::size_t HidReportDescriptor::report_bytes(ReportType type, std::uint8_t id) const {
  std::uint32_t bits = 0;
  bool any = false;
  for (const auto& f : fields)
    if (f.type == type && f.report_id == id) {
      bits = std::max(bits, f.bit_offset + f.bit_size);
      any = true;
    }
  if (!any) return 0;
  return (bits + 7) / 8 + (uses_report_ids ? 1 : 0);
}

bool HidReportDescriptor::has_pid_page() const {
  return std::any_of(fields.begin(), fields.end(), [](const HidField& f) {
    return (f.usage >> 16) == kPidPage || (f.report_usage >> 16) == kPidPage;
  });
}

HidReportDescriptor parse_hid_report_descriptor(std::span<const std::uint8_t> bytes) {
  using namespace hid_limits;
  if (bytes.size() > kDescriptorBytes)
    fail(0, std::to_string(bytes.size()) + " bytes, over the " + std::to_string(kDescriptorBytes) +
                " a descriptor can have (its length is 16 bits)");
  HidReportDescriptor out;
  std::size_t array_usages_kept = 0;
  Globals g;
  std::vector<Globals> stack;         // Push / Pop
  std::vector<Collection> collections;
  std::vector<std::uint32_t> usages;  // locals, cleared after each main item
  std::uint32_t usage_min = 0;
  bool have_usage_min = false;
  std::map<std::pair<int, int>, std::uint32_t> next_bit;  // (type, report id) -> bits used so far

  std::size_t i = 0;
  while (i < bytes.size()) {
    const std::size_t at = i;
    const std::uint8_t prefix = bytes[i++];
    if (prefix == 0xFE) {  // long item: bDataSize, bLongItemTag, data
      if (i + 2 > bytes.size()) fail(at, "long item runs past the end");
      const std::size_t size = bytes[i];
      i += 2 + size;
      if (i > bytes.size()) fail(at, "long item runs past the end");
      continue;
    }
    const std::size_t size = (prefix & 3) == 3 ? 4 : (prefix & 3);
    const int type = (prefix >> 2) & 3;
    const int tag = prefix >> 4;
    if (i + size > bytes.size()) fail(at, "item runs past the end");
    const std::span<const std::uint8_t> data = bytes.subspan(i, size);
    i += size;

    if (type == 0) {  // main
      const std::uint32_t flags = unsigned_data(data);
      if (tag == 0x8 || tag == 0x9 || tag == 0xB) {
        const ReportType rt = tag == 0x8 ? ReportType::Input : tag == 0x9 ? ReportType::Output : ReportType::Feature;
        // HID 1.11 sets no limit; Linux's parser takes up to 256 bits, and the OpenFFBoard's vendor
        // command reports use 64-bit fields. The driver refuses to use a field wider than 32 bits.
        if (g.report_size > 256) fail(at, "report size " + std::to_string(g.report_size) + " bits is over 256");
        std::uint32_t& bit = next_bit[{static_cast<int>(rt), g.report_id}];
        const bool constant = flags & 1;
        const bool variable = flags & 2;
        // Checked before a field is made: 4 bytes of Report Count claim 4 billion of them.
        const std::uint64_t report_bits = std::uint64_t{bit} + std::uint64_t{g.report_size} * g.report_count;
        if (report_bits > std::uint64_t{kReportBytes - 1} * 8)
          fail(at, std::string(type_name(rt)) + " report " + std::to_string(g.report_id) + " grows to " +
                       std::to_string((report_bits + 7) / 8) + " bytes, over the " + std::to_string(kReportBytes) +
                       " a report can have");
        if (out.fields.size() + g.report_count > kFields)
          fail(at, "more than " + std::to_string(kFields) + " fields in all");
        if (!constant && !variable) {
          array_usages_kept += std::size_t{g.report_count} * usages.size();
          if (array_usages_kept > kArrayUsages)
            fail(at, "arrays with more than " + std::to_string(kArrayUsages) + " usages in all (over every slot)");
        }
        const std::uint32_t report_usage = collections.empty() ? 0 : collections.back().pid_report;
        const std::uint32_t parent = collections.empty() ? 0 : collections.back().usage;
        for (std::uint32_t k = 0; k < g.report_count; ++k) {
          HidField f;
          f.type = rt;
          f.report_id = g.report_id;
          f.bit_offset = bit;
          f.bit_size = g.report_size;
          f.logical_min = g.logical_min;
          f.logical_max = g.logical_max;
          f.constant = constant;
          f.variable = variable;
          f.report_usage = report_usage;
          f.parent_usage = parent;
          if (constant) {
          } else if (variable) {
            if (!usages.empty()) f.usage = usages[std::min<std::size_t>(k, usages.size() - 1)];
          } else {
            f.usage = parent;
            f.array_usages = usages;
          }
          out.fields.push_back(std::move(f));
          bit += g.report_size;
        }
      } else if (tag == 0xA) {  // Collection
        const std::uint32_t u = usages.empty() ? 0 : usages.front();
        const std::uint32_t outer = collections.empty() ? 0 : collections.back().pid_report;
        collections.push_back({u, outer != 0 ? outer : (u >> 16) == kPidPage ? u : 0});
      } else if (tag == 0xC) {  // End Collection
        if (collections.empty()) fail(at, "End Collection without a Collection");
        collections.pop_back();
      } else {
        fail(at, "unknown main item tag " + std::to_string(tag));
      }
      usages.clear();
      have_usage_min = false;
    } else if (type == 1) {  // global
      switch (tag) {
        case 0x0: g.usage_page = static_cast<std::uint16_t>(unsigned_data(data)); break;
        case 0x1: g.logical_min = signed_data(data); break;
        case 0x2: g.logical_max = signed_data(data); break;
        case 0x7: g.report_size = unsigned_data(data); break;
        case 0x8: {
          const std::uint32_t id = unsigned_data(data);
          if (id == 0) fail(at, "report ID 0 is reserved");
          if (id > 255) fail(at, "report ID " + std::to_string(id) + " is over 255 (a report ID is one byte)");
          g.report_id = static_cast<std::uint8_t>(id);
          out.uses_report_ids = true;
          break;
        }
        case 0x9:
          g.report_count = unsigned_data(data);
          if (g.report_count > kUsagesPerItem)
            fail(at, "Report Count " + std::to_string(g.report_count) + " is over " + std::to_string(kUsagesPerItem));
          break;
        case 0xA: stack.push_back(g); break;
        case 0xB:
          if (stack.empty()) fail(at, "Pop without Push");
          g = stack.back();
          stack.pop_back();
          break;
        default: break;  // physical range, unit, unit exponent: not needed for commands
      }
      // A non-negative minimum with a "negative" maximum means the maximum was meant unsigned
      // (e.g. 0..255 written as one byte 0xFF), as HID 1.11 6.2.2.7 notes.
      if (tag == 0x2 && g.logical_min >= 0 && g.logical_max < 0)
        g.logical_max = static_cast<std::int32_t>(unsigned_data(data));
    } else if (type == 2) {  // local
      // A usage range's maximum only arrives after its minimum; it is expanded here, within the limit.
      switch (tag) {
        case 0x0:
          if (usages.size() >= kUsagesPerItem) fail(at, "more than " + std::to_string(kUsagesPerItem) + " usages before one main item");
          usages.push_back(full_usage(data, g.usage_page));
          break;
        case 0x1:
          usage_min = full_usage(data, g.usage_page);
          have_usage_min = true;
          break;
        case 0x2:
          if (have_usage_min) {
            const std::uint32_t last = full_usage(data, g.usage_page);
            for (std::uint32_t u = usage_min; u <= last && u - usage_min < 0x10000; ++u) {
              if (usages.size() >= kUsagesPerItem)
                fail(at, "more than " + std::to_string(kUsagesPerItem) + " usages before one main item");
              usages.push_back(u);
            }
          }
          break;
        default: break;  // designators, strings, delimiters
      }
    } else {
      fail(at, "reserved item type");
    }
  }
  if (!collections.empty()) fail(bytes.size(), "a Collection is never ended");
  return out;
}

void write_field(std::span<std::uint8_t> report, bool uses_ids, const HidField& field, std::int64_t value) noexcept {
  const std::size_t base = uses_ids ? 8 : 0;
  const auto v = static_cast<std::uint64_t>(value);
  for (std::uint32_t b = 0; b < std::min<std::uint32_t>(field.bit_size, 64); ++b) {
    const std::size_t bit = base + field.bit_offset + b;
    if (bit / 8 >= report.size()) return;
    const auto mask = static_cast<std::uint8_t>(1u << (bit % 8));
    if ((v >> b) & 1) report[bit / 8] |= mask;
    else report[bit / 8] &= static_cast<std::uint8_t>(~mask);
  }
}

std::int64_t read_field(std::span<const std::uint8_t> report, bool uses_ids, const HidField& field) noexcept {
  const std::size_t base = uses_ids ? 8 : 0;
  std::uint64_t v = 0;
  for (std::uint32_t b = 0; b < std::min<std::uint32_t>(field.bit_size, 64); ++b) {
    const std::size_t bit = base + field.bit_offset + b;
    if (bit / 8 >= report.size()) break;
    if ((report[bit / 8] >> (bit % 8)) & 1) v |= std::uint64_t{1} << b;
  }
  if (field.logical_min < 0 && field.bit_size > 0 && field.bit_size < 64 && ((v >> (field.bit_size - 1)) & 1))
    v |= ~std::uint64_t{0} << field.bit_size;
  return static_cast<std::int64_t>(v);
}

}  // namespace sandpaper::runtime::usb
