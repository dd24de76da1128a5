#pragma once
// A UsbTransport for tests: replays a recorded report descriptor, feature replies and input report
// stream, and records every transfer the driver makes, bytes included. Storage for the record is
// reserved up front, so the _rt calls do not allocate (the driver's no-allocation test relies on it).
#include <array>
#include <atomic>
#include <thread>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <vector>

#include "sandpaper/runtime/usb/transport.hpp"

namespace sandpaper::runtime::usb::testing {

enum class Op { Detach, Attach, Claim, Release, Descriptor, Output, SetFeature, GetFeature };

struct Transfer {
  Op op;
  std::array<std::uint8_t, 64> bytes{};  // Output, SetFeature: the report; GetFeature: the report ID asked for
  std::size_t size = 0;
  std::vector<std::uint8_t> data() const { return {bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(size)}; }
};

// One reply of the interrupt IN endpoint: a report, or a status (Timeout, NoDevice, ...).
struct InputEvent {
  UsbStatus status = UsbStatus::Ok;
  std::vector<std::uint8_t> report;
};

class FakeTransport final : public UsbTransport {
 public:
  FakeTransport(std::vector<std::uint8_t> descriptor, std::size_t capacity = 100000);

  // Replies to GET_REPORT (Feature) of `report_id`, used in order (the last one repeats).
  void add_feature_reply(std::uint8_t report_id, std::vector<std::uint8_t> reply);
  // Input events in order; after the last, `after_end` (default: Timeout).
  void add_input(InputEvent e) { inputs_.push_back(std::move(e)); }
  UsbStatus after_end = UsbStatus::Timeout;
  // After the last input event, keep answering with the last report (a device streaming positions).
  bool repeat_last_input = false;
  // Whether a read that does not wait (timeout 0) gets the next input event: false, the events
  // arrive only when waited for (so the open sequence leaves a test's queued positions alone);
  // true, every event has already arrived (the driver's I/O thread, which never waits).
  bool inputs_arrived = false;
  // From now every output transfer blocks until release_outputs(): a transfer that never completes.
  void hang_outputs() { hang_.store(true); }
  void release_outputs() { hang_.store(false); }
  // Output transfers blocked so far (entered while hanging).
  std::size_t hung_outputs() const { return hung_.load(); }
  // Counts transfers (reads and outputs) made on `thread`: the servo thread must make none.
  void watch_thread(std::thread::id thread) { watched_.store(thread); }
  std::size_t transfers_on_watched_thread() const { return on_watched_.load(); }
  // From this many output reports on (counted from now), every call returns NoDevice.
  void unplug_after_outputs(std::size_t n) { unplug_at_output_ = outputs_ + n; }
  // Every call from now returns NoDevice.
  void unplug() { unplugged_ = true; }
  // The next `n` output transfers time out without reaching the device (it NAKed them past the
  // timeout); n = SIZE_MAX: every one from now.
  void time_out_outputs(std::size_t n) { timeouts_left_.store(n); }

  const std::vector<Transfer>& log() const { return log_; }
  void clear_log() { log_.clear(); }
  // The longest report the driver handed over, in bytes (the log keeps at most 64 of each).
  std::size_t longest_transfer() const { return longest_; }
  bool kernel_driver_attached() const { return kernel_attached_; }
  bool claimed() const { return claimed_; }

  UsbStatus report_descriptor(std::vector<std::uint8_t>& descriptor) override;
  UsbStatus detach_kernel_driver() override;
  UsbStatus attach_kernel_driver() override;
  UsbStatus claim_interface() override;
  UsbStatus release_interface() override;
  UsbStatus read_input(std::span<std::uint8_t> buffer, std::size_t& length, unsigned timeout_ms) noexcept override;
  UsbStatus write_output(std::span<const std::uint8_t> report) noexcept override;
  UsbStatus set_feature(std::span<const std::uint8_t> report) override;
  UsbStatus get_feature(std::uint8_t report_id, std::span<std::uint8_t> buffer, std::size_t& length) override;

 private:
  void record(Op op, std::span<const std::uint8_t> bytes) noexcept;

  std::vector<std::uint8_t> descriptor_;
  std::map<std::uint8_t, std::vector<std::vector<std::uint8_t>>> feature_replies_;
  std::map<std::uint8_t, std::size_t> feature_next_;
  std::vector<InputEvent> inputs_;
  std::size_t next_input_ = 0;
  std::vector<Transfer> log_;
  std::size_t longest_ = 0;
  void note_thread() noexcept {
    if (std::this_thread::get_id() == watched_.load()) on_watched_.fetch_add(1);
  }
  std::size_t outputs_ = 0, unplug_at_output_ = std::numeric_limits<std::size_t>::max();
  // Set by the test thread while the driver's I/O thread transfers.
  std::atomic<bool> unplugged_{false}, hang_{false};
  std::atomic<std::size_t> timeouts_left_{0};
  std::atomic<std::size_t> hung_{0}, on_watched_{0};
  std::atomic<std::thread::id> watched_{};
  bool kernel_attached_ = true, claimed_ = false;
};

// Reads a hex file: bytes as two hex digits separated by white space; '#' starts a comment.
std::vector<std::uint8_t> read_hex_file(const std::filesystem::path& file);

}  // namespace sandpaper::runtime::usb::testing
