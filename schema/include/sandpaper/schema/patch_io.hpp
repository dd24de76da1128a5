#pragma once
// Binary patch-program files (docs/PATCH_FORMAT.md): 32-byte header (magic "SNDPATCH", format
// version, payload size, CRC-32 of the payload) then a little-endian payload. Deterministic: the
// same PatchProgram always gives the same bytes.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::schema {

// Thrown for a file that is not a valid patch program (bad magic, version, size or checksum).
struct PatchFormatError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// How a patch is written. Reading needs no options: each term says how it is stored.
struct PatchWriteOptions {
  // Height-field grids as IEEE 754 binary16 ("half") floats, when every force in the grid stays
  // within kCompactTolerance of the grid's largest force component; a grid that would not stays
  // float32. Halves the file of an image texture (docs/PATCH_FORMAT.md, tag 16).
  bool compact_grids = false;
};
inline constexpr double kCompactTolerance = 1e-3;

// What compact_grids did: height-field terms stored as halves and kept as float32, and the largest
// error of a stored half, as a fraction of its grid's largest force component.
struct CompactReport {
  std::size_t compacted = 0, kept = 0;
  double largest_error = 0;
};

std::vector<unsigned char> serialize(const PatchProgram& program, const PatchWriteOptions& options = {},
                                     CompactReport* report = nullptr);
// Throws PatchFormatError.
PatchProgram deserialize(const std::vector<unsigned char>& bytes);

// Writes to `<path>.tmp-XXXX` then renames, so a failed write never leaves a half file. The
// program's arrays are written from where they lie (no copy of the grids).
// Throws std::runtime_error on I/O failure.
void write_patch_file(const std::filesystem::path& path, const PatchProgram& program, const PatchWriteOptions& options = {},
                      CompactReport* report = nullptr);
// Reads the payload straight into the program's arrays (no second copy of the file in memory).
// Throws std::runtime_error (cannot read) or PatchFormatError (not a patch program).
PatchProgram read_patch_file(const std::filesystem::path& path);

// True if the file starts with the patch-program magic.
bool looks_like_patch_file(const std::filesystem::path& path);

}  // namespace sandpaper::schema
