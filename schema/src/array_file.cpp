#include "sandpaper/schema/array_file.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>

#include "sandpaper/schema/atomic_file.hpp"

namespace sandpaper::schema {

std::vector<unsigned char> encode_array(const ArrayFile& a) {
  if (a.values.size() != static_cast<std::size_t>(a.width) * a.height)
    throw ArrayFileError(ArrayFileError::Reason::WrongSize,
                         "array of " + std::to_string(a.width) + " x " + std::to_string(a.height) + " items holds " +
                             std::to_string(a.values.size()) + " values");
  std::vector<unsigned char> out;
  out.reserve(kArrayHeaderBytes + a.values.size());
  out.push_back(static_cast<unsigned char>(a.width >> 8));
  out.push_back(static_cast<unsigned char>(a.width & 0xFF));
  out.push_back(static_cast<unsigned char>(a.height >> 8));
  out.push_back(static_cast<unsigned char>(a.height & 0xFF));
  out.insert(out.end(), a.values.begin(), a.values.end());
  return out;
}

ArrayFile decode_array(const std::vector<unsigned char>& bytes, const std::string& name) {
  if (bytes.size() < kArrayHeaderBytes)
    throw ArrayFileError(ArrayFileError::Reason::WrongSize,
                         "array file '" + name + "' is " + std::to_string(bytes.size()) +
                             " bytes, shorter than its 4-byte header (width, height)");
  ArrayFile a;
  a.width = static_cast<std::uint16_t>((bytes[0] << 8) | bytes[1]);
  a.height = static_cast<std::uint16_t>((bytes[2] << 8) | bytes[3]);
  std::size_t want = kArrayHeaderBytes + static_cast<std::size_t>(a.width) * a.height;
  if (bytes.size() != want)
    throw ArrayFileError(ArrayFileError::Reason::WrongSize,
                         "array file '" + name + "' is " + std::to_string(bytes.size()) + " bytes, but its header says " +
                             std::to_string(a.width) + " x " + std::to_string(a.height) + " items, which take " +
                             std::to_string(want) + " bytes (width x height + 4)");
  a.values.assign(bytes.begin() + kArrayHeaderBytes, bytes.end());
  return a;
}

ArrayFile read_array_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw ArrayFileError(ArrayFileError::Reason::Unreadable, "cannot open array file '" + path.string() + "'");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad())
    throw ArrayFileError(ArrayFileError::Reason::Unreadable, "cannot read array file '" + path.string() + "'");
  return decode_array(bytes, path.string());
}

namespace {

void write_array(const std::filesystem::path& path, const ArrayFile& a) {
  auto bytes = encode_array(a);
  write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace

void write_depth_file(const std::filesystem::path& path, const ArrayFile& heights) { write_array(path, heights); }
void write_shade_file(const std::filesystem::path& path, const ArrayFile& picture) { write_array(path, picture); }

ArrayKind array_kind_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".depth") return ArrayKind::Depth;
  if (ext == ".shade") return ArrayKind::Shade;
  return ArrayKind::None;
}

}  // namespace sandpaper::schema
