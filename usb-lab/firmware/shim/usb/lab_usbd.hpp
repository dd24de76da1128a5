#pragma once
// The lab's side of the TinyUSB device stack shim (usbd_shim.cpp): bus events, control requests
// and endpoint transfers, delivered to TinyUSB's own HID class driver (hid_device.c) and control
// transfer code (usbd_control.c) the way usbd.c and the chip's device controller driver would.
// Every call except wait_in_transfer must be made holding the emulated core (lab_core.hpp).
#include <chrono>
#include <cstdint>
#include <span>
#include <vector>

namespace sandpaper::usb_lab::usbd {

// SET_CONFIGURATION 1 with the function's descriptors (interface, HID, endpoints): opens the HID
// driver on them (hidd_open), then the firmware's tud_mount_cb. A configured device is reset first.
bool configure(std::span<const std::uint8_t> hid_function_descriptors);
// SET_CONFIGURATION 0: resets the class driver and endpoints, then tud_umount_cb.
void deconfigure();
// Bus suspend / resume: tud_suspend_cb(remote wakeup) / tud_resume_cb, as usbd.c calls them.
void suspend(bool suspended);

struct ControlResult {
  bool stall = false;
  std::vector<std::uint8_t> data;  // IN data stage
};
// One control transfer addressed to the interface or an endpoint: SETUP, data stage (`out_data`
// for OUT requests, chunked by the 64-byte EP0), status stage, as usbd.c and usbd_control.c run it.
ControlResult control(std::uint8_t bmRequestType, std::uint8_t bRequest, std::uint16_t wValue,
                      std::uint16_t wIndex, std::uint16_t wLength, std::span<const std::uint8_t> out_data);

// A transfer the host sent to an OUT endpoint completes into the driver's queued buffer. False when
// the endpoint had no transfer queued (the bus would NAK it).
bool out_transfer(std::uint8_t ep_addr, std::span<const std::uint8_t> data);

// Waits (without the core) until the driver queued a transfer on IN endpoint `ep_addr` that was not
// yet taken, and takes a copy of it. False on timeout.
bool wait_in_transfer(std::uint8_t ep_addr, std::vector<std::uint8_t>& data, std::chrono::microseconds wait);
// The taken IN transfer reached the host (or failed): completes it to the driver (hidd_xfer_cb).
void complete_in_transfer(std::uint8_t ep_addr, bool delivered);

bool stack_initialized();  // tusb_init() ran (the firmware's USB task starts it)

}  // namespace sandpaper::usb_lab::usbd
