#include "sidewinder_ff2.hpp"

#include <vector>

namespace sandpaper::usb_lab {

// What the recorded descriptors say (SidewinderFFPDetails.md): bcdUSB 1.10, bcdDevice 0x0A00,
// class in the interface, bcdHID 1.00; iProduct "SideWinder Force Feedback 2 Joystick". The
// manufacturer string was not requested by the recording (iManufacturer 1 exists): "Microsoft" is
// ours. No serial number (iSerialNumber 0). A full-speed device: USB 1.1.
// Endpoints as recorded: interrupt IN 0x81, 64 bytes, bInterval 1; interrupt OUT 0x02, 16 bytes
// (the longest output reports, Set Effect and Custom Force Data, are 16 with their ID), bInterval 4.
std::unique_ptr<HidPidDevice> sidewinder_ff2() {
  DeviceIdentity id;
  id.vendor_id = 0x045E;
  id.product_id = 0x001B;
  id.bcd_device = 0x0A00;
  id.bcd_usb = 0x0110;
  id.manufacturer = "Microsoft";
  id.product = "SideWinder Force Feedback 2 Joystick";
  id.max_speed = "full-speed";
  const std::span<const std::uint8_t> d = sidewinder_ff2_report_descriptor();
  InterruptEndpoints ep;
  ep.in_interval = 1;
  ep.in_max_packet = 64;
  ep.out_interval = 4;
  ep.out_max_packet = 16;
  return std::make_unique<HidPidDevice>(id, std::vector<std::uint8_t>(d.begin(), d.end()), ep, 0x0100);
}

}  // namespace sandpaper::usb_lab
