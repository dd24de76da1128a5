#pragma once
// 8-bit PNG files through libpng, for the catalog's and the studio's pictures: drawn at the size
// they are shown, so they need no resampling, and writing them must not load OpenImageIO (its
// ~260 libraries take 0.3-0.4 s, more than the rest of a one-entry catalog update; compiler/image_io.hpp).
#include <cstdint>
#include <filesystem>
#include <string>

namespace sandpaper::catalog {

// Writes nx x ny pixels of `channels` (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA) bytes each, row 0 at
// the top, to `file` itself (callers write beside the target and rename). False and `why` on failure.
bool write_png_file(const std::filesystem::path& file, int nx, int ny, int channels, const std::uint8_t* pixels,
                    std::string& why);

}  // namespace sandpaper::catalog
