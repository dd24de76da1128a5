#pragma once
// A UsbFunction that passes everything to the function behind it and logs, on arrival, every
// output report it is sent (interrupt OUT and SET_REPORT), so the lab can say when each force
// value reached the device.
#include "bus_log.hpp"
#include "forwarding_function.hpp"

namespace sandpaper::usb_lab {

class LoggedFunction final : public ForwardingFunction {
 public:
  LoggedFunction(UsbFunction& inner, AppendLog<ReportRecord>& log) : ForwardingFunction(inner), log_(log) {}

  ControlReply control(const SetupPacket& setup, std::span<const std::uint8_t> out_data) override;
  void interrupt_out(std::span<const std::uint8_t> data) override;

 private:
  void note(std::uint8_t pipe, std::uint8_t type, std::span<const std::uint8_t> data) noexcept;

  AppendLog<ReportRecord>& log_;
};

}  // namespace sandpaper::usb_lab
