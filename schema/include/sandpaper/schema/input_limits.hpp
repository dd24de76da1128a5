#pragma once
// Limits on outside input, one place for all of them; docs/RELIABILITY.md lists each with the error
// it gives. Each is far above what a hand-written or shipped file needs and far below what would
// exhaust memory or time on a small machine.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace sandpaper::schema::limits {

// A material (.hmat) or workspace (.hws) source file: 4 MiB. The largest shipped file is 1.6 KB.
inline constexpr std::size_t kMaxSourceBytes = std::size_t{4} << 20;
// Errors kept per compile; past it one "too many errors" diagnostic ends the list (as clang's
// -ferror-limit). Warnings are capped at the same count, summarised the same way.
inline constexpr std::size_t kMaxErrorsPerFile = 50;
inline constexpr std::size_t kMaxWarningsPerFile = 200;
// A source line echoed under a diagnostic is clipped to this many bytes around the caret.
inline constexpr std::size_t kMaxEchoedLineBytes = 160;
// `like` chains: a material inheriting from one inheriting from ... at most this deep.
inline constexpr int kMaxLikeDepth = 64;
// An image read as a height map: at most 4096 x 4096 pixels (compiler kMaxImagePixels) and 64
// channels, its height channels as floats under 256 MiB; checked from the header, before any pixel.
inline constexpr std::uint64_t kMaxImageChannels = 64;
// An image file on disk: 512 MiB.
inline constexpr std::uint64_t kMaxImageFileBytes = std::uint64_t{512} << 20;
// A workspace: at most this many patches.
inline constexpr std::size_t kMaxWorkspacePatches = 65536;
// The force tables a workspace holds (schema::grid_bytes), each distinct material's program and each
// placed copy of one (a material placed at another size is another copy): 512 MiB in all. Patches
// share programs, but distinct textures do not: six at 4000 x 4000 samples took 1.1 GB (fuzz-led
// finding F35). A texture at the image limit is 128 MiB; the largest shipped workspace, sampler.hws, holds 8 MiB.
inline constexpr std::uint64_t kMaxWorkspaceGridBytes = std::uint64_t{512} << 20;
// Sizes and positions a workspace program may hold (m): what its reader takes, so the compiler
// refuses what it could not read back (a patch 42e-30 mm wide).
inline constexpr double kMinPlausibleLength_m = 1e-12;
inline constexpr double kMaxPlausibleLength_m = 1e12;
// A number in a calibration CSV (a force, a command, a period, a magnitude estimate): 0, or within
// these in magnitude, as a quantity in the language. Past the top a gauge fit's sums of squares
// overflow (a force of 7.5e300 N gave a gain of 1.4e296 N per unit, s.e. inf,
// exit 0); below the bottom a fitted map's bounds did not read back (F31: 1.7e-310 N, exit 3).
inline constexpr double kMinMeasurement = 1e-12;
inline constexpr double kMaxMeasurement = 1e12;
// A run: at most a day (`--duration`, s). A run that records every tick (the virtual clock, the
// simulated joystick, `--trace`) at most 2^21 ticks, about 35 min at 1 kHz: each tick's record
// is kept in memory until the run ends.
inline constexpr double kMaxRunSeconds = 86400;
inline constexpr std::uint64_t kMaxRecordedTicks = std::uint64_t{1} << 21;
// Other text inputs read whole (calibration TOML, CSV, movie, shuffle and experiment files): 64 MiB.
inline constexpr std::size_t kMaxTextFileBytes = std::size_t{64} << 20;

}  // namespace sandpaper::schema::limits

namespace sandpaper::schema {

// An input file that cannot be read as asked: missing, not a regular file (a FIFO or a device such
// as /dev/zero would block or never end), unreadable, or larger than its limit. what() names the
// path and how to fix it.
struct InputFileError : std::runtime_error {
  InputFileError(const std::string& path, const std::string& why)
      : std::runtime_error("'" + path + "': " + why), reason(why) {}
  std::string reason;  // what is wrong, without the path: "No such file or directory"
};

// The whole of a regular file, at most `max_bytes` long. Throws InputFileError.
std::string read_input_file(const std::filesystem::path& path, std::size_t max_bytes);

// True if `text` is well-formed UTF-8 (no overlong forms, surrogates or code points past U+10FFFF);
// otherwise false and `bad_offset` is the byte offset of the first byte that is not.
bool is_valid_utf8(std::string_view text, std::size_t& bad_offset) noexcept;

// `text` with each byte that does not begin a whole UTF-8 character replaced by U+FFFD: for text
// Sandpaper writes into a file a UTF-8 reader must load (a file name in another encoding inside a
// fitted map's comments, docs/RELIABILITY.md F26).
std::string replace_invalid_utf8(std::string_view text);

}  // namespace sandpaper::schema
