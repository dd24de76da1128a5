#pragma once
// A UsbFunction that passes everything to the function behind it except the faults the lab injects:
// a control request it refuses (STALL), as a device with a broken Feature report does; a GET_REPORT
// it answers late, as a device busy elsewhere does; and input reports it stops sending, as a device
// whose sensor or firmware hangs does. The stall and the delay are set before the device starts; the
// silence can be switched on from another thread while it runs.
#include <atomic>
#include <optional>
#include <thread>

#include "forwarding_function.hpp"

namespace sandpaper::usb_lab {

// HID 1.11 section 7.2: class requests GET_REPORT (0x01) and SET_REPORT (0x09), wValue = report
// type (3: Feature) << 8 | report ID.
struct ClassReport {
  std::uint8_t report_type = 3;
  std::uint8_t report_id = 0;
  bool matches(const SetupPacket& s) const {
    return (s.bmRequestType & 0x60) == 0x20 && (s.bRequest == 0x01 || s.bRequest == 0x09) &&
           (s.wValue >> 8) == report_type && (s.wValue & 0xFF) == report_id;
  }
};

class FaultyFunction final : public ForwardingFunction {
 public:
  explicit FaultyFunction(UsbFunction& inner) : ForwardingFunction(inner) {}

  // Every GET_REPORT and SET_REPORT of this report is refused from now on.
  void stall(ClassReport r) { stalled_ = r; }
  // Every GET_REPORT of this report is answered `delay` after the host asked (on ep0's thread, the
  // emulated core free meanwhile).
  void answer_late(ClassReport r, std::chrono::milliseconds delay) {
    late_ = r;
    delay_ = delay;
  }
  // From now on no input report reaches the host (the firmware's are dropped unsent).
  void silence_input() noexcept { silent_.store(true, std::memory_order_relaxed); }
  bool input_silenced() const noexcept { return silent_.load(std::memory_order_relaxed); }

  bool accepts(const SetupPacket& setup) const override { return !(stalled_ && stalled_->matches(setup)) && inner_.accepts(setup); }
  ControlReply control(const SetupPacket& setup, std::span<const std::uint8_t> out_data) override {
    if (stalled_ && stalled_->matches(setup)) return ControlReply{true, {}};
    if (late_ && late_->matches(setup) && setup.bRequest == 0x01) std::this_thread::sleep_for(delay_);
    return inner_.control(setup, out_data);
  }
  bool next_interrupt_in(std::vector<std::uint8_t>& report, std::chrono::microseconds wait) override {
    if (!input_silenced()) return inner_.next_interrupt_in(report, wait);
    std::this_thread::sleep_for(wait);
    return false;
  }

 private:
  std::optional<ClassReport> stalled_, late_;
  std::chrono::milliseconds delay_{0};
  std::atomic<bool> silent_{false};
};

}  // namespace sandpaper::usb_lab
