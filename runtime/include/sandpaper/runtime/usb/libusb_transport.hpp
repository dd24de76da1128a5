#pragma once
// The UsbTransport on libusb-1.0: a device's first HID interface, its interrupt endpoints and the
// HID class requests on its control pipe (HID 1.11 section 7.2). Also lists the HID devices present
// for `sandpaper devices`. The interrupt IN endpoint always has a transfer in flight (allocated once,
// resubmitted from its completion), so no report the device sends waits for the next read call: a
// host controller only polls an endpoint that has a transfer queued. Output and control transfers
// are synchronous and allocate a transfer inside libusb on every call (docs/USB_PID.md).
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sandpaper/runtime/usb/transport.hpp"

struct libusb_context;
struct libusb_device_handle;
struct libusb_transfer;

namespace sandpaper::runtime::usb {

struct UsbHidDeviceInfo {
  std::uint16_t vendor_id = 0, product_id = 0;
  int bus = 0, address = 0;
  int hid_interface = -1;
  std::string product;          // iProduct string when the device could be opened, else empty
  UsbStatus open_status = UsbStatus::Ok;  // AccessDenied: the udev rule is missing
  bool descriptor_read = false; // the report descriptor was read (from sysfs, without detaching the kernel driver)
  bool has_pid = false;         // ... and it has a Physical Interface Device (force-feedback) usage
  // The axes its effects can act on (Set Effect's Axes Enable: 1 for X, 2 for X and Y); 0: not read.
  // Tells a board's wheel from its joystick where both have one USB ID (the OpenFFBoard's).
  int force_axes = 0;
  std::string descriptor_error; // not empty: the descriptor was read and refused, in the parser's words
};

// Fills `descriptor_read`, `has_pid`, `force_axes` and `descriptor_error` of `info` from a report descriptor as read
// from the device. Never throws: a descriptor over the parser's limits (hid_descriptor.hpp) is kept
// as its reason, so `sandpaper devices` can say why a device will not open.
void summarise_report_descriptor(std::span<const std::uint8_t> descriptor, UsbHidDeviceInfo& info);

struct UsbHidEnumeration {
  UsbStatus status = UsbStatus::Ok;   // not Ok: USB could not be searched at all
  std::string message;                // why, in words
  std::vector<UsbHidDeviceInfo> devices;
};

// Every USB device with a HID interface. Never throws.
UsbHidEnumeration list_usb_hid_devices();

class LibusbTransport final : public UsbTransport {
 public:
  // Opens the first device with this vendor and product ID and finds its HID interface.
  // Returns NoDevice if there is none, AccessDenied without permission; `message` says more.
  static UsbStatus open(std::uint16_t vendor_id, std::uint16_t product_id, std::unique_ptr<LibusbTransport>& out,
                        std::string& message);
  ~LibusbTransport() override;

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
  LibusbTransport() = default;
  UsbStatus set_report(int type, std::span<const std::uint8_t> report, unsigned timeout_ms) noexcept;
  // The interrupt IN transfer kept in flight: submitted at the first read, resubmitted by its own
  // completion, cancelled (and waited for) before the interface is released.
  UsbStatus submit_input() noexcept;
  // The status of a failed transfer's libusb code; an I/O error from a device that no longer
  // answers is NoDevice.
  UsbStatus named(int rc) noexcept;
  void cancel_input() noexcept;
  static void on_input(libusb_transfer* transfer);

  // Reports received and not yet read, oldest first; when full the oldest is dropped (a reader
  // that far behind wants the latest position).
  struct Received {
    std::array<std::uint8_t, 64> bytes{};
    std::size_t length = 0;
  };
  static constexpr std::size_t kQueued = 8;
  std::array<Received, kQueued> received_{};
  std::size_t received_head_ = 0, received_count_ = 0;
  libusb_transfer* input_transfer_ = nullptr;
  std::array<std::uint8_t, 64> input_buffer_{};
  bool input_in_flight_ = false;
  UsbStatus input_error_ = UsbStatus::Ok;  // the IN endpoint's failure, reported by the next read

  libusb_context* context_ = nullptr;
  libusb_device_handle* handle_ = nullptr;
  int interface_ = 0;
  unsigned char endpoint_in_ = 0, endpoint_out_ = 0;  // 0: none
  int descriptor_length_ = 4096;
  bool uses_report_ids_ = true;
  bool detached_ = false;
};

// The libusb error code `code` (a negative LIBUSB_ERROR_*) as a UsbStatus.
UsbStatus usb_status_from_libusb(int code) noexcept;

}  // namespace sandpaper::runtime::usb
