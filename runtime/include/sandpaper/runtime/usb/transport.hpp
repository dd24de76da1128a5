#pragma once
// What the HID PID driver needs of a USB connection, so that it can be tested without hardware:
// libusb_transport.hpp talks to a real device, tests use a fake that replays a recorded descriptor
// and report stream. Reports are passed as on the wire: byte 0 is the report ID when the device
// uses report IDs. Transfers block and (in libusb) allocate and lock: the driver makes them on its own I/O
// thread (HidPidIo::IoThread), never on the servo thread.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace sandpaper::runtime::usb {

// Why a transfer failed. Every libusb error maps onto one of these (libusb_transport.cpp).
enum class UsbStatus {
  Ok,
  Timeout,        // no data within the timeout (interrupt IN) or the device did not answer in time
  NoDevice,       // unplugged, or never there
  AccessDenied,   // permissions: the udev rule in docs/USB_PID.md fixes it
  Busy,           // another program or kernel driver holds the interface
  NotSupported,   // the platform cannot do it (e.g. detaching kernel drivers)
  Stalled,        // the device refused the request with a STALL handshake (USB 2.0 section 8.4.5)
  Other,          // overflow, I/O error, ...
};

const char* to_string(UsbStatus status) noexcept;

// One open USB HID interface.
class UsbTransport {
 public:
  virtual ~UsbTransport() = default;

  // The interface's HID report descriptor (HID 1.11 section 7.1.1, GET_DESCRIPTOR of type 0x22).
  virtual UsbStatus report_descriptor(std::vector<std::uint8_t>& descriptor) = 0;
  // Takes the interface from the kernel's HID driver (Ok if none was attached) and gives it back.
  virtual UsbStatus detach_kernel_driver() = 0;
  virtual UsbStatus attach_kernel_driver() = 0;
  virtual UsbStatus claim_interface() = 0;
  virtual UsbStatus release_interface() = 0;

  // Reads one input report from the interrupt IN endpoint into `buffer`, waiting at most
  // `timeout_ms`; 0: only a report that has already arrived, else Timeout at once. `length` gets
  // the number of bytes received.
  virtual UsbStatus read_input(std::span<std::uint8_t> buffer, std::size_t& length,
                                  unsigned timeout_ms) noexcept = 0;
  // Sends an output report: interrupt OUT when the interface has that endpoint, else SET_REPORT
  // (Output) on the control pipe.
  virtual UsbStatus write_output(std::span<const std::uint8_t> report) noexcept = 0;
  // SET_REPORT (Feature) and GET_REPORT (Feature) on the control pipe. `buffer[0]` of get_feature
  // is the report ID asked for; `length` gets the bytes received, report ID included.
  virtual UsbStatus set_feature(std::span<const std::uint8_t> report) = 0;
  virtual UsbStatus get_feature(std::uint8_t report_id, std::span<std::uint8_t> buffer, std::size_t& length) = 0;
};

}  // namespace sandpaper::runtime::usb
