#include "fake_transport.hpp"

#include <chrono>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace sandpaper::runtime::usb::testing {

FakeTransport::FakeTransport(std::vector<std::uint8_t> descriptor, std::size_t capacity)
    : descriptor_(std::move(descriptor)) {
  log_.reserve(capacity);
}

void FakeTransport::add_feature_reply(std::uint8_t report_id, std::vector<std::uint8_t> reply) {
  feature_replies_[report_id].push_back(std::move(reply));
}

void FakeTransport::record(Op op, std::span<const std::uint8_t> bytes) noexcept {
  longest_ = std::max(longest_, bytes.size());
  if (log_.size() == log_.capacity()) return;  // never reallocate inside an _rt call
  Transfer t{op, {}, std::min(bytes.size(), std::size_t{64})};
  std::copy_n(bytes.begin(), t.size, t.bytes.begin());
  log_.push_back(t);
}

UsbStatus FakeTransport::report_descriptor(std::vector<std::uint8_t>& descriptor) {
  if (unplugged_) return UsbStatus::NoDevice;
  record(Op::Descriptor, {});
  descriptor = descriptor_;
  return UsbStatus::Ok;
}

UsbStatus FakeTransport::detach_kernel_driver() {
  if (unplugged_) return UsbStatus::NoDevice;
  record(Op::Detach, {});
  kernel_attached_ = false;
  return UsbStatus::Ok;
}

UsbStatus FakeTransport::attach_kernel_driver() {
  if (unplugged_) return UsbStatus::NoDevice;
  record(Op::Attach, {});
  kernel_attached_ = true;
  return UsbStatus::Ok;
}

UsbStatus FakeTransport::claim_interface() {
  if (unplugged_) return UsbStatus::NoDevice;
  record(Op::Claim, {});
  claimed_ = true;
  return UsbStatus::Ok;
}

UsbStatus FakeTransport::release_interface() {
  if (unplugged_) return UsbStatus::NoDevice;
  record(Op::Release, {});
  claimed_ = false;
  return UsbStatus::Ok;
}

UsbStatus FakeTransport::read_input(std::span<std::uint8_t> buffer, std::size_t& length, unsigned timeout_ms) noexcept {
  length = 0;
  note_thread();
  if (unplugged_) return UsbStatus::NoDevice;
  if (timeout_ms == 0 && !inputs_arrived) return UsbStatus::Timeout;
  if (next_input_ >= inputs_.size() && !(repeat_last_input && !inputs_.empty())) return after_end;
  const InputEvent& e = inputs_[std::min(next_input_++, inputs_.size() - 1)];
  if (e.status != UsbStatus::Ok) return e.status;
  length = std::min(e.report.size(), buffer.size());
  std::copy_n(e.report.begin(), length, buffer.begin());
  return UsbStatus::Ok;
}

UsbStatus FakeTransport::write_output(std::span<const std::uint8_t> report) noexcept {
  note_thread();
  if (hang_.load()) {
    hung_.fetch_add(1);
    while (hang_.load()) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  if (outputs_ >= unplug_at_output_) unplugged_ = true;
  if (unplugged_) return UsbStatus::NoDevice;
  if (std::size_t left = timeouts_left_.load(); left > 0) {
    if (left != std::numeric_limits<std::size_t>::max()) timeouts_left_.store(left - 1);
    return UsbStatus::Timeout;
  }
  ++outputs_;
  record(Op::Output, report);
  return UsbStatus::Ok;
}

UsbStatus FakeTransport::set_feature(std::span<const std::uint8_t> report) {
  if (unplugged_) return UsbStatus::NoDevice;
  record(Op::SetFeature, report);
  return UsbStatus::Ok;
}

UsbStatus FakeTransport::get_feature(std::uint8_t report_id, std::span<std::uint8_t> buffer, std::size_t& length) {
  length = 0;
  if (unplugged_) return UsbStatus::NoDevice;
  const std::uint8_t id[1] = {report_id};
  record(Op::GetFeature, id);
  const auto it = feature_replies_.find(report_id);
  if (it == feature_replies_.end() || it->second.empty()) return UsbStatus::Stalled;
  std::size_t& next = feature_next_[report_id];
  const auto& reply = it->second[std::min(next, it->second.size() - 1)];
  ++next;
  length = std::min(reply.size(), buffer.size());
  std::copy_n(reply.begin(), length, buffer.begin());
  return UsbStatus::Ok;
}

std::vector<std::uint8_t> read_hex_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  std::vector<std::uint8_t> bytes;
  std::string line;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string word;
    while (words >> word) {
      if (word.size() != 2) throw std::runtime_error(file.string() + ": '" + word + "' is not one hex byte");
      bytes.push_back(static_cast<std::uint8_t>(std::stoul(word, nullptr, 16)));
    }
  }
  return bytes;
}

}  // namespace sandpaper::runtime::usb::testing
