#pragma once
// What the FunctionFS front end (functionfs_device.cpp) needs of the USB device behind it: its
// identity and interface descriptors, its answers on the control pipe and its interrupt endpoints.
// The OpenFFBoard firmware compiled for the host (usb-lab/firmware/) is the one implementation;
// the front end knows nothing of HID PID.
#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sandpaper::usb_lab {

// A SETUP packet as on the wire (USB 2.0 section 9.3), fields in host byte order.
struct SetupPacket {
  std::uint8_t bmRequestType = 0;
  std::uint8_t bRequest = 0;
  std::uint16_t wValue = 0, wIndex = 0, wLength = 0;
  bool device_to_host() const { return (bmRequestType & 0x80) != 0; }
};

// The answer to one control request. Stall: the device refuses it (STALL handshake). Otherwise, for
// an IN request, `data` is sent (the front end cuts it to wLength); for an OUT request it is empty.
struct ControlReply {
  bool stall = false;
  std::vector<std::uint8_t> data;
};

// Who the device says it is: what configfs sets on the gadget (the kernel answers the device
// descriptor itself) and the speed it enumerates at.
struct DeviceIdentity {
  std::uint16_t vendor_id = 0, product_id = 0, bcd_device = 0, bcd_usb = 0x0200;
  std::uint8_t device_class = 0, device_subclass = 0, device_protocol = 0;
  std::string manufacturer, product, serial_number;
  std::string max_speed = "full-speed";   // configfs max_speed: full-speed, high-speed
};

class UsbFunction {
 public:
  virtual ~UsbFunction() = default;

  virtual DeviceIdentity identity() const = 0;
  // The function's descriptors as they appear in its configuration descriptor after the
  // configuration descriptor itself: interface, class-specific (HID 0x21) and endpoint
  // descriptors, in order. Interface numbers are the function's own, from 0.
  virtual std::vector<std::uint8_t> function_descriptors() const = 0;
  // String descriptor `index` of the device (iInterface and the like) as UTF-8; empty if none.
  virtual std::string string_descriptor(std::uint8_t index) const {
    (void)index;
    return {};
  }

  // Bus events: the host set the configuration (endpoints usable), deconfigured or reset it,
  // suspended or resumed the bus.
  virtual void configured() = 0;
  virtual void deconfigured() = 0;
  virtual void suspended(bool suspended) = 0;

  // Whether the function takes this request at all, asked before an OUT request's data stage (after
  // it, FunctionFS can no longer stall); false: the front end stalls it.
  virtual bool accepts(const SetupPacket& setup) const {
    (void)setup;
    return true;
  }
  // A control request addressed to the function (recipient interface or endpoint, any type), with
  // the data stage of an OUT request in `out_data` (wLength bytes).
  virtual ControlReply control(const SetupPacket& setup, std::span<const std::uint8_t> out_data) = 0;

  // One transfer received on the interrupt OUT endpoint.
  virtual void interrupt_out(std::span<const std::uint8_t> data) = 0;
  // The next report the device queued for its interrupt IN endpoint; false if none within `wait`.
  virtual bool next_interrupt_in(std::vector<std::uint8_t>& report, std::chrono::microseconds wait) = 0;
  // The report last taken from next_interrupt_in reached the host (true) or was dropped (false).
  virtual void interrupt_in_done(bool delivered) = 0;
};

}  // namespace sandpaper::usb_lab
