// What the hidraw device family reads of a node's device from sysfs (parse_hid_uevent): the kernel
// writes the file, but HID_NAME is the device's own product string, so any bytes can arrive.
//
// Checked: a parse that succeeds took its IDs from a well-formed HID_ID line (re-formatted and
// parsed again they come back the same); the name holds no line break.
#include <cstdint>
#include <cstdio>
#include <string>

#include "fuzz_support.hpp"
#include "sandpaper/runtime/usb/hidraw_transport.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using sandpaper::fuzz::check;
  using sandpaper::runtime::usb::HidrawNode;
  using sandpaper::runtime::usb::parse_hid_uevent;
  const std::string text(reinterpret_cast<const char*>(data), size);
  HidrawNode node;
  if (!parse_hid_uevent(text, node)) return 0;
  check(node.name.find('\n') == std::string::npos, "a name with a line break");
  char line[64];
  std::snprintf(line, sizeof line, "HID_ID=%04X:%08X:%08X\n", node.usb ? 3u : 5u, unsigned{node.vendor_id},
                unsigned{node.product_id});
  HidrawNode again;
  check(parse_hid_uevent(line, again) && again.vendor_id == node.vendor_id && again.product_id == node.product_id &&
            again.usb == node.usb,
        std::string("the IDs did not survive a round trip: ") + line);
  return 0;
}
