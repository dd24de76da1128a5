#pragma once
// A UsbFunction that hands everything to the function behind it: the base of the lab's wrappers
// (logging, fault injection), each of which overrides only what it changes.
#include "usb_function.hpp"

namespace sandpaper::usb_lab {

class ForwardingFunction : public UsbFunction {
 public:
  explicit ForwardingFunction(UsbFunction& inner) : inner_(inner) {}

  DeviceIdentity identity() const override { return inner_.identity(); }
  std::vector<std::uint8_t> function_descriptors() const override { return inner_.function_descriptors(); }
  std::string string_descriptor(std::uint8_t index) const override { return inner_.string_descriptor(index); }
  void configured() override { inner_.configured(); }
  void deconfigured() override { inner_.deconfigured(); }
  void suspended(bool s) override { inner_.suspended(s); }
  bool accepts(const SetupPacket& setup) const override { return inner_.accepts(setup); }
  ControlReply control(const SetupPacket& setup, std::span<const std::uint8_t> out_data) override {
    return inner_.control(setup, out_data);
  }
  void interrupt_out(std::span<const std::uint8_t> data) override { inner_.interrupt_out(data); }
  bool next_interrupt_in(std::vector<std::uint8_t>& report, std::chrono::microseconds wait) override {
    return inner_.next_interrupt_in(report, wait);
  }
  void interrupt_in_done(bool delivered) override { inner_.interrupt_in_done(delivered); }

 protected:
  UsbFunction& inner_;
};

}  // namespace sandpaper::usb_lab
