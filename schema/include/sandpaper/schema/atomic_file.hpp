#pragma once
// Outputs are written to a temporary file beside the target and renamed over it, so bad input or
// a crash never leaves a half-written file (DEVELOPERS.md, "Bad input ... changes nothing").
#include <filesystem>
#include <string_view>

namespace sandpaper::schema {

// Throws std::runtime_error naming the path and the OS reason on failure; the target is untouched.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace sandpaper::schema
