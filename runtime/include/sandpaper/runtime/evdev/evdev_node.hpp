#pragma once
// Input event devices (/dev/input/event*) that can play force feedback, as sysfs describes them:
// read without opening the node, so `sandpaper devices` lists them whatever this user may open.
// Bits and codes: Linux's include/uapi/linux/input-event-codes.h and Documentation/input/ff.rst.
#include <cstdint>
#include <string>
#include <vector>

namespace sandpaper::runtime::evdev {

inline constexpr unsigned kFfConstant = 0x52;    // FF_CONSTANT
inline constexpr unsigned kFfGain = 0x60;        // FF_GAIN
inline constexpr unsigned kFfAutocenter = 0x61;  // FF_AUTOCENTER
inline constexpr unsigned kAbsX = 0x00, kAbsY = 0x01, kAbsWheel = 0x08;

// One event node with force feedback. Units: none.
struct EvdevNode {
  std::string path;                  // "/dev/input/event5"
  std::string name;                  // the input device's name ("FFBoard FFBoard")
  std::uint16_t bustype = 0, vendor_id = 0, product_id = 0;  // input_id; bustype 3 is USB
  bool constant_force = false;       // FF_CONSTANT among its effects
  bool gain = false, autocenter = false;  // FF_GAIN, FF_AUTOCENTER
  int axes = 0;                      // 2: ABS_X and ABS_Y; 1: ABS_X (or ABS_WHEEL) alone; 0: neither
  std::string report_descriptor;     // sysfs file of the HID device's report descriptor, "" when not HID
  double out_interval_s = 0;         // its USB interface's interrupt OUT endpoint's interval, s (0: none found)
  bool usb() const noexcept { return bustype == 3; }
};

// Whether bit `bit` is set in a sysfs bitmap ("107030000 0": hexadecimal words of the kernel's
// unsigned long, most significant first, separated by spaces). False for malformed text.
bool sysfs_bit(const std::string& bitmap, unsigned bit, unsigned word_bits = 64) noexcept;

// An endpoint's `interval` as sysfs prints it ("1ms", "125us"), s; 0 for anything else.
double sysfs_interval_s(const std::string& text) noexcept;
// Every event node under `sysfs_root`/class/input whose device has EV_FF, sorted by number. Never throws.
std::vector<EvdevNode> list_force_feedback_nodes(const std::string& sysfs_root = "/sys");

// The node `path` names (a symlink such as /dev/input/by-id/... is followed), if it is one of `nodes`.
const EvdevNode* find_node(const std::vector<EvdevNode>& nodes, const std::string& path);

}  // namespace sandpaper::runtime::evdev
