#pragma once
// What the HID PID driver's open sequence (hid_pid_open.cpp) and its tick and I/O thread
// (hid_pid_joystick.cpp) share. Internal to the USB library.
#include <cstdint>
#include <ctime>

namespace sandpaper::runtime::usb {

// Reports read per tick at most: the device may interleave PID State reports with position
// reports, and a transport may have queued several (libusb_transport.hpp keeps 8).
inline constexpr int kReadsPerTick = 8;

// CLOCK_MONOTONIC in nanoseconds.
inline std::int64_t monotonic_ns() noexcept {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return std::int64_t{now.tv_sec} * 1'000'000'000 + now.tv_nsec;
}

}  // namespace sandpaper::runtime::usb
