#pragma once
// Pictures in and out through OpenImageIO, behind one table of functions. OpenImageIO brings about
// 260 shared libraries on Debian; loading them costs about 0.3 s and 130 MB before main(), which
// every `sandpaper` command paid, even `library search`. So the command-line programs load it on
// the first picture they read or write (libsandpaper_image_io.so; docs/performance.md, "Start-up"),
// and applications built against an install link it in (Sandpaper::image_io). The table is the
// same either way; which provider defines api() is chosen when linking (compiler/CMakeLists.txt).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sandpaper::compiler::image_io {

// Raised when the table changes shape: a module of another shape is refused, not called.
inline constexpr int kAbi = 1;

struct PictureHeader {
  int width = 0, height = 0, channels = 0;  // px, px, count
  std::vector<std::string> channel_names;    // as stored; may hold empty names
  std::string format;                        // "uint8", "half", ...
  std::size_t format_bytes = 0;              // bytes per stored channel value
};

struct Api {
  int abi = 0;
  const char* build = nullptr;  // the Sandpaper version it was built with

  // Opens a picture and reads its header only (no pixel allocated). nullptr and `why` on failure.
  // Heights are taken as stored: alpha is never premultiplied.
  void* (*open)(const std::string& path, PictureHeader& header, std::string& why) = nullptr;
  // Reads channels [first, last] of every pixel as floats (integers normalised to 0..1) into
  // `pixels` (width * height * (last - first + 1)); false and `why` also when the reader only logged
  // an error (a truncated file). Does not close.
  bool (*read)(void* picture, int first, int last, float* pixels, std::string& why) = nullptr;
  void (*close)(void* picture) = nullptr;
  // Resamples a one-channel float image nx x ny to tx x ty with the named filter ("lanczos3",
  // "catmull-rom", or "" for OpenImageIO's default).
  bool (*resize)(const float* src, int nx, int ny, float* dst, int tx, int ty, const char* filter, std::string& why) = nullptr;
  // Writes 8-bit pixels (nx x ny x channels, row 0 at the top) to `path` as PNG, first resized to
  // tx x ty with the default filter if that differs. Writes `path` itself: callers rename.
  bool (*write_png8)(const std::string& path, int nx, int ny, int channels, const std::uint8_t* pixels, int tx, int ty,
                     std::string& why) = nullptr;
  // A one-channel 16-bit PNG ("Y") in memory.
  bool (*encode_png16)(int nx, int ny, const std::uint16_t* texels, std::vector<unsigned char>& png, std::string& why) = nullptr;
};

// The table. The loading provider throws compiler::InternalError naming every place it looked when
// the module is missing or of another build (an installation fault, not the user's input).
const Api& api();

// Where the picture table comes from: "linked", or the module's path once loaded ("" before).
std::string provider();

}  // namespace sandpaper::compiler::image_io
