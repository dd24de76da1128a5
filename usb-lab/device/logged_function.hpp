#pragma once
// A UsbFunction that passes everything to the function behind it and logs, on arrival, every
// output report it is sent (interrupt OUT and SET_REPORT), so the lab can say when each force
// value reached the device.
#include "bus_log.hpp"
#include "usb_function.hpp"

namespace sandpaper::usb_lab {

class LoggedFunction final : public UsbFunction {
 public:
  LoggedFunction(UsbFunction& inner, AppendLog<ReportRecord>& log) : inner_(inner), log_(log) {}

  DeviceIdentity identity() const override { return inner_.identity(); }
  std::vector<std::uint8_t> function_descriptors() const override { return inner_.function_descriptors(); }
  std::string string_descriptor(std::uint8_t index) const override { return inner_.string_descriptor(index); }
  void configured() override { inner_.configured(); }
  void deconfigured() override { inner_.deconfigured(); }
  void suspended(bool s) override { inner_.suspended(s); }
  bool accepts(const SetupPacket& setup) const override { return inner_.accepts(setup); }
  ControlReply control(const SetupPacket& setup, std::span<const std::uint8_t> out_data) override;
  void interrupt_out(std::span<const std::uint8_t> data) override;
  bool next_interrupt_in(std::vector<std::uint8_t>& report, std::chrono::microseconds wait) override {
    return inner_.next_interrupt_in(report, wait);
  }
  void interrupt_in_done(bool delivered) override { inner_.interrupt_in_done(delivered); }

 private:
  void note(std::uint8_t pipe, std::uint8_t type, std::span<const std::uint8_t> data) noexcept;

  UsbFunction& inner_;
  AppendLog<ReportRecord>& log_;
};

}  // namespace sandpaper::usb_lab
