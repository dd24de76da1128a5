#pragma once
// Binary workspace-program files (`.wsp`, docs/PATCH_FORMAT.md, "Workspace programs"): what
// `sandpaper compile ws.hws -o ws.wsp` writes and the runtime-only player plays. A 32-byte header
// like a patch file's (magic "SNDWKSPC", format version, payload size, CRC-32 of the payload), then
// the workspace's name and size and each placed patch with its whole patch program (as
// write_patch_file would write it). Little-endian, deterministic.
#include <filesystem>

#include "sandpaper/schema/patch_io.hpp"
#include "sandpaper/schema/workspace_program.hpp"

namespace sandpaper::schema {

inline constexpr std::uint32_t kWorkspaceFormatVersion = 1;

// Written to a temporary file and renamed. Throws std::runtime_error on I/O failure.
void write_workspace_program_file(const std::filesystem::path& path, const WorkspaceProgram& workspace,
                                  const PatchWriteOptions& options = {});
// Throws std::runtime_error (cannot read) or PatchFormatError (not a valid workspace program).
WorkspaceProgram read_workspace_program_file(const std::filesystem::path& path);
// True if the file starts with the workspace-program magic.
bool looks_like_workspace_program_file(const std::filesystem::path& path);

}  // namespace sandpaper::schema
