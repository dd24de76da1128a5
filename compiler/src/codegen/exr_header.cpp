#include "exr_header.hpp"

#include <algorithm>
#include <cstdint>
#include <fstream>

namespace sandpaper::compiler {

namespace {

// Version field flag (OpenEXR file layout, "Version Field").
constexpr std::uint32_t kMultipart = 0x1000;
// The longest name or type: 255 bytes with the long-names flag, else 31, but OpenEXR Core 3.1
// reads a 42-byte name without the flag (F44's file), so the walk takes what Core takes.
constexpr std::size_t kLongestWord = 255;

// An attribute's name or type: bytes up to a NUL, at most kLongestWord of them. nullopt if the file
// ends first; an over-long one is returned cut one byte past the limit.
std::optional<std::string> read_word(std::istream& in) {
  std::string word;
  for (char c = 0; in.get(c);) {
    if (c == '\0') return word;
    word += c;
    if (word.size() > kLongestWord) return word;
  }
  return std::nullopt;
}

// A name for a message: as written if it is short printable ASCII (as every standard name is).
std::string shown(const std::string& name) {
  if (name.empty() || name.size() > 64) return "an attribute";
  for (const char c : name)
    if (c < 0x20 || c > 0x7e) return "an attribute";
  return "attribute '" + name + "'";
}

// Core refuses these too, but a file it refused so still took 4 s under ASan (F44).
std::string too_long(std::uint64_t at, const char* what) {
  return "the OpenEXR header is damaged: the attribute at byte " + std::to_string(at) + " has a " + what +
         " longer than " + std::to_string(kLongestWord) + " bytes";
}

}  // namespace

std::optional<std::string> exr_header_overrun(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::array<unsigned char, 8> head{};
  if (!in.read(reinterpret_cast<char*>(head.data()), head.size()) ||
      !std::equal(kExrMagic.begin(), kExrMagic.end(), head.begin()))
    return std::nullopt;
  const std::uint32_t version =
      head[4] | (std::uint32_t{head[5]} << 8) | (std::uint32_t{head[6]} << 16) | (std::uint32_t{head[7]} << 24);
  if ((version & 0xff) != 2) return std::nullopt;
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(in.tellg());
  in.seekg(8);
  const auto cut_short = [&] {
    return "the OpenEXR header is cut short: the file ends at byte " + std::to_string(size) + " inside it";
  };
  // Header: attributes (name, type, 4-byte little-endian size, value), then an empty name. A
  // multipart file has one header a part, and an empty header after the last.
  while (true) {
    for (bool first = true;; first = false) {
      const auto at = static_cast<std::uint64_t>(in.tellg());
      const auto name = read_word(in);
      if (!name) return cut_short();
      if (name->empty()) {
        if (first && (version & kMultipart)) return std::nullopt;  // the empty header: the list's end
        break;
      }
      if (name->size() > kLongestWord) return too_long(at, "name");
      const auto type = read_word(in);
      if (!type) return cut_short();
      if (type->size() > kLongestWord) return too_long(at, "type");
      std::array<unsigned char, 4> b{};
      if (!in.read(reinterpret_cast<char*>(b.data()), b.size())) return cut_short();
      const auto claimed = static_cast<std::int32_t>(b[0] | (std::uint32_t{b[1]} << 8) | (std::uint32_t{b[2]} << 16) |
                                                     (std::uint32_t{b[3]} << 24));
      const auto after = static_cast<std::uint64_t>(in.tellg());
      if (claimed < 0)
        return "the OpenEXR header is damaged: its " + shown(*name) + " at byte " + std::to_string(at) + " claims " +
               std::to_string(claimed) + " bytes, a negative size";
      if (static_cast<std::uint64_t>(claimed) > size - after)
        return "the OpenEXR header is cut short: its " + shown(*name) + " at byte " + std::to_string(at) + " claims " +
               std::to_string(claimed) + " bytes, and the file has " + std::to_string(size - after) + " after its size";
      in.seekg(static_cast<std::streamoff>(after + static_cast<std::uint64_t>(claimed)));
    }
    if (!(version & kMultipart)) return std::nullopt;
  }
}

}  // namespace sandpaper::compiler
