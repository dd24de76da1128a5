// What the evdev device family reads of an input device from sysfs (sysfs_bit on capabilities/ev,
// ff and abs): the kernel writes the bitmaps, but a reader must not trust a file it did not write.
//
// Checked: for text the kernel could have written (hex words of at most 16 digits, one space
// between them), every bit agrees with a decoder that reads each word with strtoull; for any text,
// no crash and no bit past the words given.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "sandpaper/runtime/evdev/evdev_node.hpp"

namespace {

bool kernel_like(const std::string& text, std::vector<std::uint64_t>& words) {
  std::istringstream in(text);
  std::string w, rebuilt;
  while (in >> w) {
    if (w.size() > 16 || w.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos) return false;
    words.push_back(std::strtoull(w.c_str(), nullptr, 16));
    rebuilt += (rebuilt.empty() ? "" : " ") + w;
  }
  return !words.empty() && rebuilt == text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using sandpaper::fuzz::check;
  using sandpaper::runtime::evdev::sysfs_bit;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::uint64_t> words;
  const bool wellformed = kernel_like(text, words);
  const unsigned bits = static_cast<unsigned>(std::min<std::size_t>(64 * (words.size() + 1), 4096));
  for (unsigned bit = 0; bit < bits; ++bit) {
    const bool got = sysfs_bit(text, bit);
    if (!wellformed) continue;
    const std::size_t index = bit / 64;
    const bool want = index < words.size() && ((words[words.size() - 1 - index] >> (bit % 64)) & 1);
    check(got == want, "bit " + std::to_string(bit) + " of '" + text + "' read as " + (got ? "set" : "clear"));
  }
  return 0;
}
