// The input-event-node driver's arithmetic and its view of sysfs, without a device; the lab plays it
// on the OpenFFBoard firmware through the kernel's hid-pidff (tests/usb-lab, `usb-lab.evdev`).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "sandpaper/runtime/evdev/evdev_joystick.hpp"
#include "sandpaper/runtime/evdev/evdev_node.hpp"

namespace fs = std::filesystem;
using namespace sandpaper::runtime::evdev;

namespace {

// Linux 6.1 drivers/hid/usbhid/hid-pidff.c, pidff_rescale_signed, as the kernel computes it (C
// integer division truncates toward zero): what reaches the device for a level.
std::int32_t kernel_rescale(std::int32_t level, std::int32_t min, std::int32_t max) {
  return level == 0 ? 0 : level > 0 ? level * max / 0x7fff : level * min / -0x8000;
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text << "\n";
}

}  // namespace

TEST(EvdevLevel, EveryCommandReachesTheDeviceExactlyThroughHidPidff) {
  // The OpenFFBoard's Magnitude is -10000..10000 (usb_hid_ffb_desc.c); the others are ranges HID
  // PID devices declare (8-bit, 16-bit, asymmetric).
  const std::pair<std::int32_t, std::int32_t> ranges[] = {{-10000, 10000}, {-255, 255}, {-128, 127}, {-32768, 32767}, {-32767, 32767}};
  for (const auto& [lo, hi] : ranges) {
    std::int16_t previous = -32768;
    for (std::int32_t c = lo; c <= hi; ++c) {
      const std::int16_t level = level_for_command(c, lo, hi);
      ASSERT_EQ(kernel_rescale(level, lo, hi), c) << "command " << c << " in [" << lo << ", " << hi << "] as level " << level;
      ASSERT_EQ(command_for_level(level, lo, hi), c);
      ASSERT_GE(level, previous) << "levels rise with the command";
      previous = level;
    }
  }
  EXPECT_EQ(level_for_command(20000, -10000, 10000), 0x7fff) << "clamped to the range";
  EXPECT_EQ(level_for_command(-20000, -10000, 10000), -0x8000);
  EXPECT_EQ(level_for_command(5, 0, 255), 0) << "an unsigned Magnitude is refused at open; no level means nothing";
}

TEST(EvdevSysfs, BitmapsAreReadAsTheKernelPrintsThem) {
  // bitmap_print_to_pagebuf-style: words of unsigned long, most significant first, no leading zeros.
  EXPECT_TRUE(sysfs_bit("1", 0));
  EXPECT_FALSE(sysfs_bit("1", 1));
  EXPECT_TRUE(sysfs_bit("8000000000000000", 63));
  EXPECT_TRUE(sysfs_bit("10 0", 68));
  EXPECT_FALSE(sysfs_bit("10 0", 4));
  // FF_CONSTANT (0x52), FF_GAIN (0x60), FF_AUTOCENTER (0x61): bits 18, 32 and 33 of the second word.
  const std::string ff = "300040000 0";
  EXPECT_TRUE(sysfs_bit(ff, kFfConstant));
  EXPECT_TRUE(sysfs_bit(ff, kFfGain));
  EXPECT_TRUE(sysfs_bit(ff, kFfAutocenter));
  EXPECT_FALSE(sysfs_bit(ff, 0x50));  // FF_RUMBLE
  EXPECT_FALSE(sysfs_bit("", 0));
  EXPECT_FALSE(sysfs_bit("xyz", 0));
  EXPECT_FALSE(sysfs_bit("1", 64)) << "a bit past the words given is clear";
  EXPECT_TRUE(sysfs_bit("ff", 7, 32));
}

TEST(EvdevSysfs, EndpointIntervalsAreReadAsTheKernelPrintsThem) {
  EXPECT_DOUBLE_EQ(sysfs_interval_s("1ms"), 0.001);
  EXPECT_DOUBLE_EQ(sysfs_interval_s("10ms"), 0.010);
  EXPECT_DOUBLE_EQ(sysfs_interval_s("125us"), 125e-6);  // a high-speed endpoint's microframe
  EXPECT_EQ(sysfs_interval_s("0ms"), 0.0);
  EXPECT_EQ(sysfs_interval_s("1s"), 0.0);
  EXPECT_EQ(sysfs_interval_s("ms"), 0.0);
  EXPECT_EQ(sysfs_interval_s(""), 0.0);
  EXPECT_EQ(sysfs_interval_s("nan ms"), 0.0);
}

TEST(EvdevSysfs, ListsOnlyEventNodesWithForceFeedbackInNumberOrder) {
  const fs::path root = fs::temp_directory_path() / ("sandpaper-evdev-sysfs-" + std::to_string(::getpid()));
  fs::remove_all(root);
  // A joystick with force feedback (EV_SYN, EV_KEY, EV_ABS, EV_FF: bits 0, 1, 3, 21), as event10;
  // a wheel (ABS_X alone) as event3; a keyboard without EV_FF as event4.
  const auto device = [&](const std::string& event, const std::string& input, const std::string& ev, const std::string& ff,
                          const std::string& abs, const std::string& name, bool hid) {
    const fs::path in = root / "devices" / input;
    write(in / "capabilities/ev", ev);
    write(in / "capabilities/ff", ff);
    write(in / "capabilities/abs", abs);
    write(in / "name", name);
    write(in / "id/bustype", "0003");
    write(in / "id/vendor", "1209");
    write(in / "id/product", "ffb0");
    if (hid) {
      write(in / "device/report_descriptor", "x");
      // The USB interface (here the HID device's parent): an IN and an OUT interrupt endpoint, as
      // drivers/usb/core/endpoint.c shows them; the OUT one every 4 ms.
      write(in / "ep_81/direction", "in");
      write(in / "ep_81/type", "Interrupt");
      write(in / "ep_81/interval", "1ms");
      write(in / "ep_01/direction", "out");
      write(in / "ep_01/type", "Interrupt");
      write(in / "ep_01/interval", "4ms");
    }
    fs::create_directories(root / "class/input" / event);
    fs::create_directory_symlink(in, root / "class/input" / event / "device");
  };
  device("event10", "input10", "20000b", "300040000 0", "3", "FFBoard FFBoard", true);
  device("event3", "input3", "20000b", "40000 0", "1", "A wheel", false);
  device("event4", "input4", "120013", "0", "0", "A keyboard", false);
  const auto nodes = list_force_feedback_nodes(root.string());
  ASSERT_EQ(nodes.size(), 2u);
  EXPECT_EQ(nodes[0].path, "/dev/input/event3");
  EXPECT_EQ(nodes[0].axes, 1);
  EXPECT_TRUE(nodes[0].constant_force);
  EXPECT_FALSE(nodes[0].gain);
  EXPECT_TRUE(nodes[0].report_descriptor.empty());
  EXPECT_EQ(nodes[1].path, "/dev/input/event10");
  EXPECT_EQ(nodes[1].name, "FFBoard FFBoard");
  EXPECT_EQ(nodes[1].axes, 2);
  EXPECT_TRUE(nodes[1].usb());
  EXPECT_EQ(nodes[1].vendor_id, 0x1209);
  EXPECT_EQ(nodes[1].product_id, 0xffb0);
  EXPECT_TRUE(nodes[1].gain && nodes[1].autocenter);
  EXPECT_FALSE(nodes[1].report_descriptor.empty());
  EXPECT_DOUBLE_EQ(nodes[1].out_interval_s, 0.004) << "the OUT endpoint's interval, not the IN one's";
  EXPECT_EQ(nodes[0].out_interval_s, 0.0) << "no USB interface found: unknown";
  EXPECT_EQ(find_node(nodes, "/dev/input/event10"), &nodes[1]);
  EXPECT_EQ(find_node(nodes, "/dev/input/event4"), nullptr);
  fs::remove_all(root);
}
