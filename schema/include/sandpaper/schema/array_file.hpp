#pragma once
// Sandpaper's own array files (Minsky 1995, Appendix B, "Array format"): a 2-byte big-endian width,
// a 2-byte big-endian height, then width x height unsigned 8-bit values, row-major, row 0 the top
// of the picture. By convention (the name, not the data, says which): ".depth" files hold heights,
// 0 the lowest; ".shade" files hold the picture Sandpaper drew, luminance with 0 = white.
// A file whose size is not width * height + 4 bytes is an error, as it was in Sandpaper.
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace sandpaper::schema {

struct ArrayFile {
  std::uint16_t width = 0, height = 0;
  std::vector<std::uint8_t> values;  // width * height, row-major, row 0 at the top
};

// Why an array file could not be used; the message names the file and the reason.
struct ArrayFileError : std::runtime_error {
  enum class Reason { Unreadable, WrongSize };
  ArrayFileError(Reason r, const std::string& message) : std::runtime_error(message), reason(r) {}
  Reason reason;
};

inline constexpr std::size_t kArrayHeaderBytes = 4;
// The largest side the 2-byte header can state; callers check before filling an ArrayFile.
inline constexpr int kMaxArraySide = 65535;

// Bytes of a file: header then values. Throws ArrayFileError (WrongSize: values.size() != width * height).
std::vector<unsigned char> encode_array(const ArrayFile& a);
// Parses a file's bytes; `name` appears in messages. Throws ArrayFileError (WrongSize: shorter than
// the header, or not width * height + 4 bytes; the message gives both sizes).
ArrayFile decode_array(const std::vector<unsigned char>& bytes, const std::string& name);
// Throws ArrayFileError (Unreadable: cannot open or read; WrongSize as decode_array).
ArrayFile read_array_file(const std::filesystem::path& path);

// Written atomically (atomic_file.hpp); throw std::runtime_error on I/O failure and ArrayFileError
// as encode_array. The two differ only in meaning: heights (0 lowest) or a picture (0 white).
void write_depth_file(const std::filesystem::path& path, const ArrayFile& heights);
void write_shade_file(const std::filesystem::path& path, const ArrayFile& picture);

// What a path names by its extension (case-insensitive): ".depth", ".shade", or neither.
enum class ArrayKind { None, Depth, Shade };
ArrayKind array_kind_of(const std::filesystem::path& path);

}  // namespace sandpaper::schema
