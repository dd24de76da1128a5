#pragma once
// A PNG file's chunk structure, walked before a decoder sees the file (internal to the compiler).
// libpng allocates each chunk at the length the file claims before reading it, and OpenImageIO,
// through which height maps are read, offers no bound on that: a 447-byte PNG whose text chunk
// claimed 1.8 GB took 1.8 GB (docs/RELIABILITY.md, F20).
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace sandpaper::compiler {

// The eight bytes every PNG starts with (PNG specification, 5.2).
inline constexpr std::array<unsigned char, 8> kPngSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

// A chunk length or header field: four bytes, most significant first (PNG specification, 7.1).
inline std::uint32_t png_be32(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

// For a file that starts with the PNG signature: why its chunks cannot be whole (one that runs past
// the end of the file, or no IEND chunk before the end), else nullopt. nullopt too for any other
// file, and for one that cannot be opened (the decoder says why). Reads 8 bytes a chunk.
std::optional<std::string> png_chunks_overrun(const std::filesystem::path& file);

}  // namespace sandpaper::compiler
