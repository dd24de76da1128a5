#include "logged_function.hpp"

#include <algorithm>

namespace sandpaper::usb_lab {

void LoggedFunction::note(std::uint8_t pipe, std::uint8_t type, std::span<const std::uint8_t> data) noexcept {
  ReportRecord r;
  r.t_ns = monotonic_ns();
  r.pipe = pipe;
  r.type = type;
  r.length = static_cast<std::uint8_t>(std::min<std::size_t>(data.size(), 255));
  std::copy_n(data.begin(), std::min(data.size(), sizeof r.bytes), r.bytes);
  log_.append(r);
}

ControlReply LoggedFunction::control(const SetupPacket& setup, std::span<const std::uint8_t> out_data) {
  constexpr std::uint8_t kClassInterfaceOut = 0x21, kSetReport = 0x09;
  if (setup.bmRequestType == kClassInterfaceOut && setup.bRequest == kSetReport)
    note('c', static_cast<std::uint8_t>(setup.wValue >> 8), out_data);
  return inner_.control(setup, out_data);
}

void LoggedFunction::interrupt_out(std::span<const std::uint8_t> data) {
  note('i', 2, data);
  inner_.interrupt_out(data);
}

}  // namespace sandpaper::usb_lab
