// libusb-1.0 calls behind UsbTransport. HID class requests (HID 1.11 section 7.2): GET_REPORT 0x01
// and SET_REPORT 0x09 with wValue = (report type << 8) | report ID, type 1 input, 2 output, 3 feature;
// the report descriptor is GET_DESCRIPTOR (0x06) of type 0x22 addressed to the interface.
#include "sandpaper/runtime/usb/libusb_transport.hpp"

#include <libusb-1.0/libusb.h>

#include <sys/time.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

#include "sandpaper/runtime/usb/hid_descriptor.hpp"

namespace sandpaper::runtime::usb {
namespace {

// A control request (report descriptor, Feature reports) may take this long: the 5 s USB 2.0
// section 9.2.6.4 allows a request to complete, and Linux's own USB_CTRL_GET_TIMEOUT and
// USB_CTRL_SET_TIMEOUT (include/linux/usb.h), which usbhid waits for the same reports. Only the open
// sequence makes them; a device busy elsewhere (or a starved emulated one) answers a Block Load
// later than 1 s and would otherwise fail an open that a moment's patience completes.
constexpr unsigned kControlTimeoutMs = 5000;
// An output report waits this long for the device to take it. A timed-out interrupt OUT transfer is
// cancelled and its report lost; with a short timeout, a device that re-arms its OUT endpoint more
// slowly than that after each report (the lab's firmware under load: 10-40 ms) NAKs the X report
// every cycle while the Y report, sent after the wait, gets through: X starves. The driver's
// watchdog, not this timeout, bounds how long a device may take no force.
constexpr unsigned kOutputTimeoutMs = 100;
constexpr std::uint8_t kHidClass = 3;
constexpr std::uint8_t kHidDescriptorType = 0x21, kReportDescriptorType = 0x22;
constexpr std::uint8_t kGetReport = 0x01, kSetReport = 0x09;
constexpr int kOutputReport = 2, kFeatureReport = 3;
// bmRequestType: direction (bit 7), type (bits 5-6: standard 0, class 1), recipient interface (1).
constexpr std::uint8_t kStandardInterfaceIn = 0x81, kClassInterfaceIn = 0xA1, kClassInterfaceOut = 0x21;

struct HidInterface {
  int number = -1;
  unsigned char in = 0, out = 0;
  int descriptor_length = 4096;
};

// The first HID interface of the active (else first) configuration.
HidInterface find_hid_interface(libusb_device* device) {
  HidInterface found;
  libusb_config_descriptor* config = nullptr;
  if (libusb_get_active_config_descriptor(device, &config) != 0 && libusb_get_config_descriptor(device, 0, &config) != 0)
    return found;
  for (int i = 0; i < config->bNumInterfaces && found.number < 0; ++i) {
    const libusb_interface& itf = config->interface[i];
    if (itf.num_altsetting < 1) continue;
    const libusb_interface_descriptor& alt = itf.altsetting[0];
    if (alt.bInterfaceClass != kHidClass) continue;
    found.number = alt.bInterfaceNumber;
    for (int e = 0; e < alt.bNumEndpoints; ++e) {
      const libusb_endpoint_descriptor& ep = alt.endpoint[e];
      if ((ep.bmAttributes & 3) != LIBUSB_TRANSFER_TYPE_INTERRUPT) continue;
      if (ep.bEndpointAddress & LIBUSB_ENDPOINT_IN) found.in = ep.bEndpointAddress;
      else found.out = ep.bEndpointAddress;
    }
    // The HID class descriptor (HID 1.11 6.2.1) carries the report descriptor's length at bytes 7-8.
    const unsigned char* extra = alt.extra;
    for (int k = 0; k + 1 < alt.extra_length && extra[k] > 0; k += extra[k])
      if (extra[k + 1] == kHidDescriptorType && k + 8 < alt.extra_length && extra[k] >= 9)
        found.descriptor_length = extra[k + 7] | (extra[k + 8] << 8);
  }
  libusb_free_config_descriptor(config);
  return found;
}

// Linux exposes each HID interface's report descriptor in sysfs, readable without detaching the
// kernel driver: /sys/bus/usb/devices/<bus>-<ports>:<config>.<interface>/<hid>/report_descriptor.
bool sysfs_report_descriptor(libusb_device* device, int interface_number, std::vector<std::uint8_t>& out) {
  std::uint8_t ports[8];
  const int n = libusb_get_port_numbers(device, ports, 8);
  if (n <= 0) return false;
  std::string name = std::to_string(libusb_get_bus_number(device)) + "-";
  for (int i = 0; i < n; ++i) name += (i ? "." : "") + std::to_string(ports[i]);
  std::error_code ec;
  for (const auto& dir : std::filesystem::directory_iterator("/sys/bus/usb/devices", ec)) {
    const std::string entry = dir.path().filename().string();
    if (entry.rfind(name + ":", 0) != 0 || !entry.ends_with("." + std::to_string(interface_number))) continue;
    for (const auto& hid : std::filesystem::directory_iterator(dir.path(), ec)) {
      std::ifstream in(hid.path() / "report_descriptor", std::ios::binary);
      if (!in) continue;
      out.assign(std::istreambuf_iterator<char>(in), {});
      return !out.empty();
    }
  }
  return false;
}

}  // namespace

const char* to_string(UsbStatus status) noexcept {
  switch (status) {
    case UsbStatus::Ok: return "ok";
    case UsbStatus::Timeout: return "timed out";
    case UsbStatus::NoDevice: return "no device (unplugged or not present)";
    case UsbStatus::AccessDenied: return "access denied (permissions)";
    case UsbStatus::Busy: return "busy (held by another program or driver)";
    case UsbStatus::NotSupported: return "not supported on this platform";
    case UsbStatus::Stalled: return "stalled (the device refused the request)";
    case UsbStatus::Other: return "USB error";
  }
  return "USB error";
}

UsbStatus usb_status_from_libusb(int code) noexcept {
  switch (code) {
    case LIBUSB_SUCCESS: return UsbStatus::Ok;
    case LIBUSB_ERROR_TIMEOUT: return UsbStatus::Timeout;
    case LIBUSB_ERROR_NO_DEVICE:
    case LIBUSB_ERROR_NOT_FOUND: return UsbStatus::NoDevice;
    case LIBUSB_ERROR_ACCESS: return UsbStatus::AccessDenied;
    case LIBUSB_ERROR_BUSY: return UsbStatus::Busy;
    case LIBUSB_ERROR_NOT_SUPPORTED: return UsbStatus::NotSupported;
    case LIBUSB_ERROR_PIPE: return UsbStatus::Stalled;
    default: return UsbStatus::Other;
  }
}

void summarise_report_descriptor(std::span<const std::uint8_t> descriptor, UsbHidDeviceInfo& info) {
  info.descriptor_read = false;
  info.has_pid = false;
  info.force_axes = 0;
  info.descriptor_error.clear();
  try {
    const HidReportDescriptor d = parse_hid_report_descriptor(descriptor);
    info.has_pid = d.has_pid_page();
    if (d.find(ReportType::Output, pid::kSetEffectReport, kUsageX))
      info.force_axes = d.find(ReportType::Output, pid::kSetEffectReport, kUsageY) ? 2 : 1;
    info.descriptor_read = true;
  } catch (const HidDescriptorError& e) {
    info.descriptor_error = e.what();
  }
}

UsbHidEnumeration list_usb_hid_devices() {
  UsbHidEnumeration out;
  libusb_context* context = nullptr;
  if (const int rc = libusb_init(&context); rc != 0) {
    out.status = usb_status_from_libusb(rc);
    out.message = std::string("USB is not available here (libusb_init: ") + libusb_strerror(rc) + ")";
    return out;
  }
  libusb_device** list = nullptr;
  const ssize_t count = libusb_get_device_list(context, &list);
  if (count < 0) {
    out.status = usb_status_from_libusb(static_cast<int>(count));
    out.message = std::string("cannot list USB devices (") + libusb_strerror(static_cast<int>(count)) + ")";
    libusb_exit(context);
    return out;
  }
  for (ssize_t i = 0; i < count; ++i) {
    libusb_device* device = list[i];
    libusb_device_descriptor dd{};
    if (libusb_get_device_descriptor(device, &dd) != 0) continue;
    const HidInterface hid = find_hid_interface(device);
    if (hid.number < 0) continue;
    UsbHidDeviceInfo info;
    info.vendor_id = dd.idVendor;
    info.product_id = dd.idProduct;
    info.bus = libusb_get_bus_number(device);
    info.address = libusb_get_device_address(device);
    info.hid_interface = hid.number;
    libusb_device_handle* handle = nullptr;
    info.open_status = usb_status_from_libusb(libusb_open(device, &handle));
    if (handle) {
      unsigned char text[128];
      if (dd.iProduct && libusb_get_string_descriptor_ascii(handle, dd.iProduct, text, sizeof text) > 0)
        info.product = reinterpret_cast<const char*>(text);
      libusb_close(handle);
    }
    std::vector<std::uint8_t> descriptor;
    if (sysfs_report_descriptor(device, hid.number, descriptor)) summarise_report_descriptor(descriptor, info);
    out.devices.push_back(std::move(info));
  }
  libusb_free_device_list(list, 1);
  libusb_exit(context);
  return out;
}

UsbStatus LibusbTransport::open(std::uint16_t vendor_id, std::uint16_t product_id,
                                std::unique_ptr<LibusbTransport>& out, std::string& message) {
  std::unique_ptr<LibusbTransport> t(new LibusbTransport());
  if (const int rc = libusb_init(&t->context_); rc != 0) {
    t->context_ = nullptr;
    message = std::string("USB is not available here (libusb_init: ") + libusb_strerror(rc) + ")";
    return usb_status_from_libusb(rc);
  }
  libusb_device** list = nullptr;
  const ssize_t count = libusb_get_device_list(t->context_, &list);
  if (count < 0) {
    message = std::string("cannot list USB devices (") + libusb_strerror(static_cast<int>(count)) + ")";
    return usb_status_from_libusb(static_cast<int>(count));
  }
  UsbStatus status = UsbStatus::NoDevice;
  message = "no USB device with that vendor and product ID";
  for (ssize_t i = 0; i < count && !t->handle_; ++i) {
    libusb_device_descriptor dd{};
    if (libusb_get_device_descriptor(list[i], &dd) != 0 || dd.idVendor != vendor_id || dd.idProduct != product_id) continue;
    const HidInterface hid = find_hid_interface(list[i]);
    if (hid.number < 0) {
      message = "the device has no HID interface";
      continue;
    }
    const int rc = libusb_open(list[i], &t->handle_);
    status = usb_status_from_libusb(rc);
    if (rc != 0) {
      t->handle_ = nullptr;
      message = std::string("cannot open the device (") + libusb_strerror(rc) + ")";
      continue;
    }
    t->interface_ = hid.number;
    t->endpoint_in_ = hid.in;
    t->endpoint_out_ = hid.out;
    t->descriptor_length_ = hid.descriptor_length;
  }
  libusb_free_device_list(list, 1);
  if (!t->handle_) return status;
  if (!t->endpoint_in_) {
    message = "the HID interface has no interrupt IN endpoint";
    return UsbStatus::Other;
  }
  message.clear();
  out = std::move(t);
  return UsbStatus::Ok;
}

LibusbTransport::~LibusbTransport() {
  if (handle_) cancel_input();
  if (input_transfer_ && !input_in_flight_) libusb_free_transfer(input_transfer_);
  if (handle_) libusb_close(handle_);
  if (context_) libusb_exit(context_);
}

UsbStatus LibusbTransport::report_descriptor(std::vector<std::uint8_t>& descriptor) {
  descriptor.assign(static_cast<std::size_t>(descriptor_length_ > 0 ? descriptor_length_ : 4096), 0);
  const int rc = libusb_control_transfer(handle_, kStandardInterfaceIn,
                                         LIBUSB_REQUEST_GET_DESCRIPTOR, kReportDescriptorType << 8,
                                         static_cast<std::uint16_t>(interface_), descriptor.data(),
                                         static_cast<std::uint16_t>(descriptor.size()), kControlTimeoutMs);
  if (rc < 0) return usb_status_from_libusb(rc);
  descriptor.resize(static_cast<std::size_t>(rc));
  try {
    uses_report_ids_ = parse_hid_report_descriptor(descriptor).uses_report_ids;
  } catch (const HidDescriptorError&) {
  }
  return UsbStatus::Ok;
}

UsbStatus LibusbTransport::detach_kernel_driver() {
  const int active = libusb_kernel_driver_active(handle_, interface_);
  if (active == LIBUSB_ERROR_NOT_SUPPORTED || active == 0) return UsbStatus::Ok;
  if (active < 0) return usb_status_from_libusb(active);
  const int rc = libusb_detach_kernel_driver(handle_, interface_);
  if (rc == 0) detached_ = true;
  return usb_status_from_libusb(rc);
}

UsbStatus LibusbTransport::attach_kernel_driver() {
  if (!detached_) return UsbStatus::Ok;
  detached_ = false;
  return usb_status_from_libusb(libusb_attach_kernel_driver(handle_, interface_));
}

UsbStatus LibusbTransport::claim_interface() { return usb_status_from_libusb(libusb_claim_interface(handle_, interface_)); }
UsbStatus LibusbTransport::release_interface() {
  cancel_input();
  return usb_status_from_libusb(libusb_release_interface(handle_, interface_));
}

UsbStatus LibusbTransport::named(int rc) noexcept {
  const UsbStatus s = usb_status_from_libusb(rc);
  if (s != UsbStatus::Other) return s;
  // A device that leaves the bus fails the transfers in flight with an I/O error (EPROTO,
  // ESHUTDOWN) before the kernel reports it gone: ask it for its status (USB 2.0 section 9.4.5).
  // A device that answers had a transfer fail; one that does not is gone from the host's view.
  std::uint8_t status[2];
  return libusb_control_transfer(handle_, 0x80, LIBUSB_REQUEST_GET_STATUS, 0, 0, status, 2, 100) == 2 ? s
                                                                                                      : UsbStatus::NoDevice;
}

UsbStatus LibusbTransport::submit_input() noexcept {
  if (!input_transfer_) {
    input_transfer_ = libusb_alloc_transfer(0);
    if (!input_transfer_) return UsbStatus::Other;
  }
  // No timeout: the transfer waits in the host controller's schedule until the device sends.
  libusb_fill_interrupt_transfer(input_transfer_, handle_, endpoint_in_, input_buffer_.data(),
                                 static_cast<int>(input_buffer_.size()), &LibusbTransport::on_input, this, 0);
  const int rc = libusb_submit_transfer(input_transfer_);
  input_in_flight_ = rc == 0;
  return usb_status_from_libusb(rc);
}

void LibusbTransport::on_input(libusb_transfer* transfer) {
  auto* self = static_cast<LibusbTransport*>(transfer->user_data);
  self->input_in_flight_ = false;
  switch (transfer->status) {
    case LIBUSB_TRANSFER_COMPLETED: {
      if (transfer->actual_length > 0) {
        if (self->received_count_ == kQueued) {  // drop the oldest
          self->received_head_ = (self->received_head_ + 1) % kQueued;
          --self->received_count_;
        }
        Received& r = self->received_[(self->received_head_ + self->received_count_) % kQueued];
        r.length = std::min(static_cast<std::size_t>(transfer->actual_length), r.bytes.size());
        std::copy_n(self->input_buffer_.begin(), r.length, r.bytes.begin());
        ++self->received_count_;
      }
      if (const UsbStatus s = self->submit_input(); s != UsbStatus::Ok) self->input_error_ = s;
      return;
    }
    case LIBUSB_TRANSFER_CANCELLED: return;
    case LIBUSB_TRANSFER_NO_DEVICE: self->input_error_ = UsbStatus::NoDevice; return;
    case LIBUSB_TRANSFER_STALL: self->input_error_ = UsbStatus::Stalled; return;
    default: self->input_error_ = UsbStatus::Other; return;  // named by the read that reports it
  }
}

void LibusbTransport::cancel_input() noexcept {
  if (!input_in_flight_) return;
  libusb_cancel_transfer(input_transfer_);
  // The cancellation completes through the event loop; a device that is gone completes it at once.
  for (int i = 0; i < 100 && input_in_flight_; ++i) {
    timeval wait{0, 10'000};
    libusb_handle_events_timeout_completed(context_, &wait, nullptr);
  }
}

UsbStatus LibusbTransport::read_input(std::span<std::uint8_t> buffer, std::size_t& length, unsigned timeout_ms) noexcept {
  length = 0;
  if (!input_in_flight_ && input_error_ == UsbStatus::Ok && received_count_ == 0)
    if (const UsbStatus s = submit_input(); s != UsbStatus::Ok) return s;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  if (timeout_ms == 0 && received_count_ == 0) {  // only what has already arrived: run the completions due
    timeval now{0, 0};
    libusb_handle_events_timeout_completed(context_, &now, nullptr);
  }
  while (received_count_ == 0 && input_error_ == UsbStatus::Ok) {
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return UsbStatus::Timeout;
    timeval wait{static_cast<time_t>(left.count() / 1'000'000), static_cast<suseconds_t>(left.count() % 1'000'000)};
    libusb_handle_events_timeout_completed(context_, &wait, nullptr);
  }
  if (received_count_ > 0) {
    const Received& r = received_[received_head_];
    length = std::min(r.length, buffer.size());
    std::copy_n(r.bytes.begin(), length, buffer.begin());
    received_head_ = (received_head_ + 1) % kQueued;
    --received_count_;
    return UsbStatus::Ok;
  }
  const UsbStatus error = input_error_ == UsbStatus::Other ? named(LIBUSB_ERROR_IO) : input_error_;
  input_error_ = error;
  // A stall or I/O error is reported once; the next read tries again. An unplugged device stays gone.
  if (error != UsbStatus::NoDevice) input_error_ = UsbStatus::Ok;
  return error;
}

UsbStatus LibusbTransport::set_report(int type, std::span<const std::uint8_t> report, unsigned timeout_ms) noexcept {
  const std::uint8_t id = uses_report_ids_ && !report.empty() ? report[0] : 0;
  const int rc = libusb_control_transfer(handle_, kClassInterfaceOut,
                                         kSetReport, static_cast<std::uint16_t>((type << 8) | id),
                                         static_cast<std::uint16_t>(interface_), const_cast<std::uint8_t*>(report.data()),
                                         static_cast<std::uint16_t>(report.size()), timeout_ms);
  return rc < 0 ? usb_status_from_libusb(rc) : UsbStatus::Ok;
}

UsbStatus LibusbTransport::write_output(std::span<const std::uint8_t> report) noexcept {
  if (!endpoint_out_) return set_report(kOutputReport, report, kOutputTimeoutMs);
  int sent = 0;
  const int rc = libusb_interrupt_transfer(handle_, endpoint_out_, const_cast<std::uint8_t*>(report.data()),
                                           static_cast<int>(report.size()), &sent, kOutputTimeoutMs);
  return named(rc);
}

UsbStatus LibusbTransport::set_feature(std::span<const std::uint8_t> report) {
  return set_report(kFeatureReport, report, kControlTimeoutMs);
}

UsbStatus LibusbTransport::get_feature(std::uint8_t report_id, std::span<std::uint8_t> buffer, std::size_t& length) {
  const int rc = libusb_control_transfer(handle_, kClassInterfaceIn,
                                         kGetReport, static_cast<std::uint16_t>((kFeatureReport << 8) | report_id),
                                         static_cast<std::uint16_t>(interface_), buffer.data(),
                                         static_cast<std::uint16_t>(buffer.size()), kControlTimeoutMs);
  length = rc > 0 ? static_cast<std::size_t>(rc) : 0;
  return rc < 0 ? usb_status_from_libusb(rc) : UsbStatus::Ok;
}

}  // namespace sandpaper::runtime::usb
