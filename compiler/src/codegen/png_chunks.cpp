#include "png_chunks.hpp"

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>

namespace sandpaper::compiler {

namespace {

// A chunk's type for a message: its four bytes if they are letters (as every PNG type is), else hex.
std::string type_name(const unsigned char* t) {
  std::string s;
  for (int i = 0; i < 4; ++i)
    if (!((t[i] >= 'A' && t[i] <= 'Z') || (t[i] >= 'a' && t[i] <= 'z'))) {
      static const char* hex = "0123456789abcdef";
      s = "0x";
      for (int j = 0; j < 4; ++j) s += std::string{hex[t[j] >> 4], hex[t[j] & 15]};
      return s;
    }
  return "'" + std::string(reinterpret_cast<const char*>(t), 4) + "'";
}

}  // namespace

std::optional<std::string> png_chunks_overrun(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::array<unsigned char, 8> head{};
  if (!in.read(reinterpret_cast<char*>(head.data()), head.size()) || head != kPngSignature) return std::nullopt;
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(in.tellg());
  std::uint64_t at = kPngSignature.size();
  // Each chunk: length (4 bytes, big-endian), type (4), data (length), CRC (4).
  while (true) {
    if (size - at < 12) return "the PNG is cut short: it ends at byte " + std::to_string(size) + " without its IEND chunk";
    in.seekg(static_cast<std::streamoff>(at));
    if (!in.read(reinterpret_cast<char*>(head.data()), head.size())) return std::nullopt;
    const std::uint64_t length = png_be32(head.data());
    if (length > size - at - 12)
      return "the PNG is cut short: its chunk " + type_name(head.data() + 4) + " at byte " + std::to_string(at) + " claims " +
             std::to_string(length) + " bytes, and the file has " + std::to_string(size - at - 12) + " after its header";
    if (std::memcmp(head.data() + 4, "IEND", 4) == 0) return std::nullopt;
    at += 12 + length;
  }
}

}  // namespace sandpaper::compiler
