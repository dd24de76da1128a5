#pragma once
// What every fuzz target shares: failing loudly on a broken invariant, a scratch folder for readers
// that take only paths, JSON output as the CLI prints it, headers fixed up so that mutations reach
// the field parsers, and playing a program on the simulated joystick with the clamp checked.
//
// A target catches only the exceptions its reader documents for bad input. Anything else (a
// std::logic_error, std::bad_alloc, a nlohmann exception, a crash, a sanitizer report) escapes to
// libFuzzer and is a finding.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace sandpaper::fuzz {

// The source tree (library/, calibration/, examples/), compiled in by fuzz/CMakeLists.txt.
std::filesystem::path source_dir();

// Prints "fuzz invariant broken: <what>" and aborts, so libFuzzer saves the input.
[[noreturn]] void fail(const std::string& what);
inline void check(bool holds, const std::string& what) {
  if (!holds) fail(what);
}

// Known defects (issue 16) a campaign may step over while they are being fixed, named in
// $SANDPAPER_FUZZ_KNOWN (comma-separated): "json-utf8" (JSON output throws type_error 316 on
// non-UTF-8 text), "readback" (a compiled program the reader refuses), "unplayable" (a compiled
// program the runtime refuses or that gives a non-finite force). Unset, as in the replay tests,
// every one of them is a failure.
bool known_defect_tolerated(std::string_view name);

// A per-process folder under /tmp, created on first use and removed at exit.
const std::filesystem::path& scratch_dir();
// Replaces `path` with `bytes` (one file reused by every input).
void write_file(const std::filesystem::path& path, std::string_view bytes);
// The whole of the file at `path` (empty if it cannot be read), in one read of its size.
std::string read_file(const std::filesystem::path& path);

// Serialises `j` as the CLI does (nlohmann::json::dump). A type_error 316 (invalid UTF-8) is a
// finding unless "json-utf8" is tolerated.
void dump_json(const nlohmann::json& j);

// A binary file with a 32-byte header (magic, u32 version, u32 flags, u64 payload size, u32 CRC-32
// of the payload, 4 bytes padding; schema/src/patch_io.cpp): `data` with that header made valid.
// If `data` already starts with `magic` and holds a whole header, its payload is what follows the
// header; otherwise all of `data` is the payload. Flags and padding are kept from `data`.
std::vector<unsigned char> with_valid_header(const std::uint8_t* data, std::size_t size, std::string_view magic,
                                             std::uint32_t version);

}  // namespace sandpaper::fuzz
