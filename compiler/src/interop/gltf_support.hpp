#pragma once
// What the glTF writer and reader share (docs/GLTF.md): the names Sandpaper writes, base64 data
// URIs, and 16-bit greyscale PNGs in memory (OpenImageIO). Private to the compiler library.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sandpaper::compiler::gltf {

// The extension (ISO/IEC 23090-14; Khronos glTF extensions/2.0/Vendor/MPEG_haptic_material).
inline constexpr const char* kExtension = "MPEG_haptic_material";
// Sandpaper's own block in the haptic material's `extras`, and its layout version.
inline constexpr const char* kExtrasKey = "sandpaper";
inline constexpr int kExtrasVersion = 2;
// Version 1 named the compiled force and roughness `max_lateral_force_N` and `roughness`; version 2
// says `compiled_...`, as every report does. Import reads both.
inline constexpr int kExtrasVersionOldNames = 1;
inline constexpr const char* kPngDataUriPrefix = "data:image/png;base64,";
// Largest 16-bit value: heights are texel / kTexelMax of the height range.
inline constexpr double kTexelMax = 65535.0;

std::string base64_encode(const std::vector<unsigned char>& bytes);
// nullopt for a character outside the alphabet, bad padding or a length that is not a multiple of 4.
std::optional<std::vector<unsigned char>> base64_decode(std::string_view text);
// A URI's percent-encoding undone ("heights%20x.png" -> "heights x.png"); nullopt for a '%' not
// followed by two hex digits.
std::optional<std::string> percent_decode(std::string_view uri);

// A greyscale 16-bit PNG of nx x ny texels, row 0 the top row. Throws std::runtime_error if
// OpenImageIO cannot write one (a broken installation, not the user's input).
std::vector<unsigned char> encode_png16(int nx, int ny, const std::vector<std::uint16_t>& texels);

// A decoded haptic texture, 0..65535.
struct Png16 {
  int nx = 0, ny = 0;
  std::vector<std::uint16_t> texels;  // row-major, row 0 the top row
};
// Decodes `bytes` as a 16-bit greyscale, non-interlaced PNG (what encode_png16 writes) of at most
// `max_pixels` texels, checked from the header before anything is allocated for pixels. nullopt
// with `why` (one line) for anything else: another PNG kind, a bad CRC, a cut or corrupt stream.
std::optional<Png16> decode_png16(const std::vector<unsigned char>& bytes, long long max_pixels, std::string& why);

// decode_gltf_value_png (gltf_document.hpp) is defined beside decode_png16, with which it shares the decoder.

}  // namespace sandpaper::compiler::gltf

namespace sandpaper::compiler::gltf {

// The two force rules the exported heights are read with (docs/GLTF.md, "Heights and forces"); the
// writer checks its own output through them and the reader uses them, so both agree by construction.
// Grating: n texels over one period; force sample i (at u = i * period / n) is
// F_i = -k (h_i - h_{i-1}) / (period / n), wrapped. h in m, k in N, F in N.
std::vector<float> grating_forces(const std::vector<double>& h, double period_m, double k_N);
// Height field: nx * ny heights (row 0 at -y), central differences, one-sided at clamped edges,
// wrapped when `repeat` (as compiler/src/codegen/height_field.cpp builds its fields). Fills fx, fy (N).
void height_field_forces(const std::vector<double>& h, int nx, int ny, double dx_m, double dy_m, bool repeat,
                         double k_N, std::vector<float>& fx, std::vector<float>& fy);

}  // namespace sandpaper::compiler::gltf
