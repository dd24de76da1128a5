#pragma once
// An OpenEXR file's header attributes, walked before a decoder sees the file (internal to the
// compiler). OpenEXR Core allocates an attribute it does not know at the size the file claims, up
// to 2 GiB, before reading it: a 513-byte file claiming 994,377,728 bytes made it map that much
// (docs/RELIABILITY.md, F44), as libpng did for a PNG's chunks (png_chunks.hpp, F20).
#include <array>
#include <filesystem>
#include <optional>
#include <string>

namespace sandpaper::compiler {

// The four bytes every OpenEXR file starts with (OpenEXR file layout, "Magic Number": 20000630 as a
// little-endian int).
inline constexpr std::array<unsigned char, 4> kExrMagic{0x76, 0x2f, 0x31, 0x01};

// For a file that starts with the OpenEXR magic number: why its header cannot be whole (an
// attribute whose size is negative or runs past the end of the file, a name or type over 255
// bytes, or a file that ends inside the header), else nullopt. nullopt too for any other file, for
// a version other than 2 and for one that cannot be opened (the decoder says why). Reads each
// attribute's name, type and size, never its value. Source: OpenEXR file layout, "Header" and
// "Attribute Layout".
std::optional<std::string> exr_header_overrun(const std::filesystem::path& file);

}  // namespace sandpaper::compiler
