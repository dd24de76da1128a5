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

std::vector<unsigned char> serialize(const PatchProgram& program);
// Throws PatchFormatError.
PatchProgram deserialize(const std::vector<unsigned char>& bytes);

// Writes to `<path>.tmp-XXXX` then renames, so a failed write never leaves a half file.
// Throws std::runtime_error on I/O failure.
void write_patch_file(const std::filesystem::path& path, const PatchProgram& program);
// Throws std::runtime_error (cannot read) or PatchFormatError (not a patch program).
PatchProgram read_patch_file(const std::filesystem::path& path);

// True if the file starts with the patch-program magic.
bool looks_like_patch_file(const std::filesystem::path& path);

}  // namespace sandpaper::schema
