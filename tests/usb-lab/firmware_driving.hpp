#pragma once
// Driving the OpenFFBoard firmware compiled for the host (usb-lab/firmware) as the USB lab's
// FunctionFS front end and Sandpaper's HID PID driver do (docs/USB_PID.md "What the driver sends"),
// for the firmware's tests: one test program per main class, since the firmware runs once per
// process. Each program defines firmware(). Cited lines are in
// ../shared/third_party/openffboard/Firmware/FFBoard at commit 160af91.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <span>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "openffboard_firmware.hpp"

namespace sandpaper::usb_lab {

// The process's firmware, started and configured by the host once (each test program defines it,
// with started_once and its main class).
OpenFFBoardFirmware& firmware();

// Main class `main` started and configured on the first call; the same firmware after (one per process).
inline OpenFFBoardFirmware& started_once(MainClass main) {
  static std::unique_ptr<OpenFFBoardFirmware> fw = [main] {
    auto f = OpenFFBoardFirmware::start(main);
    f->configured();
    return f;
  }();
  return *fw;
}

using Bytes = std::vector<std::uint8_t>;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// A byte in which a recorded descriptor file and the firmware built here differ.
struct DescriptorChange {
  std::size_t offset;
  std::uint8_t in_file;
  std::uint8_t in_firmware;
};

inline Bytes read_hex_file(const std::filesystem::path& path);

// The report descriptor the firmware answers GET_DESCRIPTOR (Report) with, as the host and the
// driver ask for it, compared with a recorded file of `size` bytes in tests/runtime/usb/data/ after
// `changes` (the bytes the firmware built here changed since the file was expanded; once the file is
// regenerated from the firmware's commit these checks fail: then drop the list).
inline void expect_report_descriptor(const std::string& file, std::size_t size, std::span<const DescriptorChange> changes) {
  Bytes expected = read_hex_file(std::filesystem::path(SANDPAPER_SOURCE_DIR) / "tests/runtime/usb/data" / file);
  ASSERT_EQ(expected.size(), size);
  for (const DescriptorChange& c : changes) {
    ASSERT_EQ(expected[c.offset], c.in_file) << "offset " << c.offset;
    expected[c.offset] = c.in_firmware;
  }
  const ControlReply r = firmware().control(SetupPacket{0x81, 0x06, 0x2200, 0, 4096}, {});
  ASSERT_FALSE(r.stall);
  EXPECT_EQ(r.data, expected);
}

// A .hex test data file: hex bytes, '#' to the end of the line is a comment.
inline Bytes read_hex_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  Bytes out;
  std::string line;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string word;
    while (words >> word) out.push_back(static_cast<std::uint8_t>(std::stoul(word, nullptr, 16)));
  }
  return out;
}

inline void put16(Bytes& b, std::size_t at, int v) {
  b[at] = static_cast<std::uint8_t>(v & 0xff);
  b[at + 1] = static_cast<std::uint8_t>((v >> 8) & 0xff);
}

inline std::int16_t i16(const Bytes& b, std::size_t at) {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(b[at] | (b[at + 1] << 8)));
}

// HID class requests on the control pipe (HID 1.11 section 7.2), interface 0, report type Feature (3).
inline ControlReply set_feature(const Bytes& report) {
  SetupPacket s{0x21, 0x09, static_cast<std::uint16_t>(0x0300 | report[0]), 0, static_cast<std::uint16_t>(report.size())};
  return firmware().control(s, report);
}

inline ControlReply get_feature(std::uint8_t id, std::uint16_t length) {
  SetupPacket s{0xA1, 0x01, static_cast<std::uint16_t>(0x0300 | id), 0, length};
  return firmware().control(s, {});
}

// Output reports go to the interrupt OUT endpoint (the driver prefers it when the interface has one).
inline void output(const Bytes& report) { firmware().interrupt_out(report); }

// Device Control (report 0x0C, a bitmask: HidFFB.cpp:209-232): 0x01 enable, 0x02 disable, 0x08 reset.
inline void device_control(std::uint8_t bits) { output({0x0C, bits}); }

// Set Constant Force (0x05, FFB_SetConstantForce_Data_t, ffb_defs.h:341-346).
inline void constant_force(std::uint8_t block, int magnitude) {
  Bytes r(4, 0);
  r[0] = 0x05;
  r[1] = block;
  put16(r, 2, magnitude);
  output(r);
}

// The driver's open sequence for one axis's constant force effect (docs/USB_PID.md, step 5):
// Create New Effect, Block Load, Set Effect, Set Constant Force 0, Effect Operation start.
// Returns the effect block index the firmware gave.
inline std::uint8_t open_constant_force_effect(int axis) {
  EXPECT_FALSE(set_feature({0x11, 0x01, 0x00, 0x00}).stall);  // type 1 = constant, byte count 0
  const ControlReply load = get_feature(0x12, 5);
  EXPECT_FALSE(load.stall);
  EXPECT_EQ(load.data.size(), 5u);  // report ID (hid_device.c prepends it) + FFB_BlockLoad_Feature_Data_t
  if (load.data.size() < 3) return 0;
  EXPECT_EQ(load.data[0], 0x12);
  EXPECT_EQ(load.data[2], 1) << "Block Load status: 1 = success";
  const std::uint8_t block = load.data[1];

  // FFB_SetEffect_t (ffb_defs.h:200-220): 18 bytes.
  Bytes e(18, 0);
  e[0] = 0x01;
  e[1] = block;
  e[2] = 0x01;            // constant force
  put16(e, 3, 0xFFFF);    // duration: infinite
  e[11] = 255;            // gain
  e[13] = axis == 0 ? 0x01 : 0x02;  // Axes Enable: this axis only, Direction Enable clear
  put16(e, 14, axis == 0 ? 36000 : 0);  // direction X at its logical maximum on the X effect
  put16(e, 16, 0);
  output(e);
  constant_force(block, 0);
  output({0x0A, block, 0x01, 0x01});  // Effect Operation: start, loop count 1
  return block;
}

template <class Done>
inline bool eventually(Done done, milliseconds limit);

// How long a condition the firmware's 1 kHz thread brings about may take to hold: eventually()
// returns as soon as it does, so a generous limit costs nothing, and a loaded machine (a CI run
// beside stress-ng) can starve that thread for tens of milliseconds.
constexpr milliseconds kSettle{5000};

struct OpenDevice {
  std::uint8_t x_block = 0;
  std::uint8_t y_block = 0;
};

// docs/USB_PID.md "Open": PID Pool, Device Control reset then enable, X then Y effects (X alone
// on a one-axis main class).
inline OpenDevice open_like_the_driver() {
  for (int a = 0; a < firmware().axes(); ++a) firmware().set_position(a, 0.0);
  const ControlReply pool = get_feature(0x13, 5);
  EXPECT_FALSE(pool.stall);
  EXPECT_GE(pool.data.size(), 4u);
  if (pool.data.size() >= 4) {
    EXPECT_GE(pool.data[3], 2) << "simultaneous effects";
  }
  device_control(0x08);
  device_control(0x01);
  OpenDevice d;
  d.x_block = open_constant_force_effect(0);
  if (firmware().axes() > 1) d.y_block = open_constant_force_effect(1);
  // A stick that moved before (an earlier test) keeps the axis damper working for a few
  // milliseconds (Axis.cpp calculateAxisEffects); start from rest.
  EXPECT_TRUE(eventually([](const FirmwareState& s) { return s.torque[0] == 0 && s.torque[1] == 0; }, kSettle));
  return d;
}

// Polls the firmware's state until `done` holds or `limit` passes.
template <class Done>
inline bool eventually(Done done, milliseconds limit) {
  const auto until = Clock::now() + limit;
  while (Clock::now() < until) {
    if (done(firmware().state())) return true;
    std::this_thread::sleep_for(milliseconds(1));
  }
  return done(firmware().state());
}

// Checks `hold` on every state seen for `span`.
template <class Hold>
inline bool always(Hold hold, milliseconds span) {
  const auto until = Clock::now() + span;
  while (Clock::now() < until) {
    if (!hold(firmware().state())) return false;
    std::this_thread::sleep_for(milliseconds(1));
  }
  return true;
}

// The next input report (ID 1) from the interrupt IN endpoint, skipping PID State reports (ID 2).
inline bool next_position_report(Bytes& report, milliseconds limit) {
  const auto until = Clock::now() + limit;
  while (Clock::now() < until) {
    if (!firmware().next_interrupt_in(report, std::chrono::duration_cast<std::chrono::microseconds>(milliseconds(50)))) {
      continue;
    }
    firmware().interrupt_in_done(true);
    if (!report.empty() && report[0] == 0x01) return true;
  }
  return false;
}

}  // namespace sandpaper::usb_lab
