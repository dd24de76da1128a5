#pragma once
// What crossed the bus and what the firmware did with it, timestamped on CLOCK_MONOTONIC (shared by
// every process in the guest, so the host program's tick times compare directly): each output
// report the device received, each torque its drivers were given. Appends are lock-free into
// storage reserved up front, so logging does not perturb the firmware's timing; what does not fit
// is counted, not stored.
#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace sandpaper::usb_lab {

std::int64_t monotonic_ns() noexcept;

struct ReportRecord {
  std::int64_t t_ns = 0;
  std::uint8_t pipe = 0;     // 'i': interrupt OUT, 'c': SET_REPORT on the control pipe
  std::uint8_t type = 0;     // HID report type of a SET_REPORT (2 output, 3 feature); 2 on interrupt OUT
  std::uint8_t length = 0;
  std::uint8_t bytes[24] = {};  // the report's first bytes, report ID first (a Set Effect report is 18 bytes)
};

struct TorqueRecord {
  std::int64_t t_ns = 0;
  std::int32_t axis = 0;
  std::int32_t torque = 0;
};

template <class Record>
class AppendLog {
 public:
  explicit AppendLog(std::size_t capacity) : records_(capacity) {}
  void append(const Record& r) noexcept {
    const std::size_t i = next_.fetch_add(1, std::memory_order_relaxed);
    if (i < records_.size()) records_[i] = r;
  }
  std::span<const Record> records() const noexcept {
    return {records_.data(), std::min(next_.load(), records_.size())};
  }
  std::size_t dropped() const noexcept {
    const std::size_t n = next_.load();
    return n > records_.size() ? n - records_.size() : 0;
  }

 private:
  std::vector<Record> records_;
  std::atomic<std::size_t> next_{0};
};

// reports.csv: t_ns,pipe,type,bytes (hex); torque.csv: t_ns,axis,torque. Written to a temporary
// file and renamed. Throws std::runtime_error naming the file when it cannot be written.
void write_report_log(const std::string& path, std::span<const ReportRecord> records);
void write_torque_log(const std::string& path, std::span<const TorqueRecord> records);

}  // namespace sandpaper::usb_lab
