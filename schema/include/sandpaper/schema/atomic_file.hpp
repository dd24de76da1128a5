#pragma once
// Outputs are written to a temporary file beside the target and renamed over it, so bad input or
// a crash never leaves a half-written file (DEVELOPERS.md, "Bad input ... changes nothing").
#include <filesystem>
#include <string_view>
#include <vector>

namespace sandpaper::schema {

// Throws std::runtime_error naming the path and the OS reason on failure; the target is untouched.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);
// The same for a file made of several pieces written in order (no copy joins them first).
void write_file_atomically(const std::filesystem::path& path, const std::vector<std::string_view>& parts);

}  // namespace sandpaper::schema
